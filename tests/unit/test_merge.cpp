// Tests of hbos/merge.hpp: a model fitted on shards and merged is bit-identical to the model
// fitted on all rows (same model-file text, same scores), under every mergeable spec, any shard
// split and any merge order; non-mergeable specs and inconsistent summaries are refused.

#include <hbos/merge.hpp>
#include <hbos/model_file.hpp>

#include "../support/mixed_features.hpp"
#include "../support/shard_merges.hpp"

#include <catch2/catch.hpp>
#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

// Every member of the class template compiles for both scalar types.
template class hbos::ShardedFit<float>;
template class hbos::ShardedFit<double>;

namespace {

using hbos::test::mixed_features;
using hbos::test::same_bits;

template <class Scalar>
using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

std::vector<std::pair<std::string, hbos::HbosParams>> mergeable_modes() {
  std::vector<std::pair<std::string, hbos::HbosParams>> modes;
  modes.emplace_back("default (5 bins x 5 shifts)", hbos::HbosParams{});
  hbos::HbosParams p;
  p.feature.binning.shifts = 1;
  p.feature.binning.bins = 10;
  modes.emplace_back("classic static 10", p);
  p = {};
  p.feature.binning.rule = hbos::BinCountRule::Sqrt;
  modes.emplace_back("sqrt rule with shifts", p);
  p.feature.binning.rule = hbos::BinCountRule::Sturges;
  p.feature.tail = hbos::Tail::Upper;
  modes.emplace_back("sturges rule, upper tail", p);
  p = {};
  p.feature.binning.method = hbos::BinningMethod::FixedWidth;
  p.feature.binning.width = 0.3;
  p.feature.binning.origin = -0.05;
  p.feature.binning.shifts = 2;
  p.feature.tail = hbos::Tail::Lower;
  modes.emplace_back("fixed width 0.3 x 2 shifts, lower tail", p);
  p = {};
  p.features.resize(5);
  p.features[1].binning.method = hbos::BinningMethod::FixedWidth;
  p.features[1].binning.width = 0.5;
  p.features[3] = hbos::angle_feature(12);
  p.features[3].binning.shifts = 3;
  p.features[4].binning.rule = hbos::BinCountRule::Sqrt;
  p.scoring.empty_bin_count = 0.3;
  modes.emplace_back("per-feature specs with a periodic feature", p);
  p.features[3].binning.rule = hbos::BinCountRule::Sqrt;
  modes.emplace_back("periodic sqrt rule", p);
  return modes;
}

/// Row shards of x at random boundaries (1 to 6 shards, some of one row).
template <class Scalar>
std::vector<Matrix<Scalar>> split(const Matrix<Scalar>& x, std::mt19937& rng) {
  std::uniform_int_distribution<int> pieces(1, 6);
  const int k = pieces(rng);
  std::vector<Eigen::Index> cuts = {0, x.rows()};
  std::uniform_int_distribution<Eigen::Index> at(1, x.rows() - 1);
  for (int i = 1; i < k; ++i) cuts.push_back(at(rng));
  cuts.push_back(x.rows() - 1);  // a one-row shard at the end
  return hbos::test::row_shards(x, std::move(cuts));
}

template <class Scalar>
void check_merged_equals_whole(std::uint32_t seed, const hbos::HbosParams& params) {
  std::mt19937 rng(seed);
  const Matrix<Scalar> x = mixed_features<Scalar>(seed, 200 + 97 * seed, true);
  const auto whole = hbos::Hbos<Scalar>::fit(x, params);
  const auto shards = split(x, rng);
  const auto merged = hbos::fit_sharded(shards, params);
  CHECK(hbos::to_model_text(merged) == hbos::to_model_text(whole));
  Matrix<Scalar> q(2 * x.rows(), x.cols());
  q << x, (x.array() * Scalar(1.7) - Scalar(1)).matrix();
  CHECK(same_bits(merged.score(q), whole.score(q)));

  // The summaries reduce in any order (a tree, reversed) to the same model.
  const auto range = hbos::test::range_merged_in_reverse(shards);
  const hbos::ShardedFit<Scalar> plan(range, params);
  const hbos::CountSummary total = hbos::test::counts_merged_as_tree(plan, shards);
  CHECK(hbos::to_model_text(plan.model(total)) == hbos::to_model_text(whole));
}

}  // namespace

TEST_CASE("a model merged from shards is bit-identical to the whole fit", "[merge]") {
  for (const auto& [name, params] : mergeable_modes()) {
    SECTION(name) {
      REQUIRE(hbos::mergeable(params, 5));
      for (std::uint32_t seed = 1; seed <= 6; ++seed) {
        check_merged_equals_whole<double>(seed, params);
        check_merged_equals_whole<float>(seed, params);
      }
    }
  }
}

TEST_CASE("specs that need the whole data are refused, naming the feature", "[merge]") {
  const Eigen::MatrixXd x = mixed_features<double>(1, 100, true);
  const auto range = hbos::summarize_range(x);
  hbos::HbosParams p;
  p.feature.binning.method = hbos::BinningMethod::EqualFrequency;
  CHECK_FALSE(hbos::mergeable(p, 5));
  CHECK_THROWS_WITH(hbos::ShardedFit<double>(range, p),
                    Catch::Contains("feature 0 cannot be fitted by shards: EqualFrequency"));
  for (const auto rule : {hbos::BinCountRule::Scott, hbos::BinCountRule::FreedmanDiaconis,
                          hbos::BinCountRule::BirgeRozenblac}) {
    p = {};
    p.features.resize(5);
    p.features[2].binning.rule = rule;
    CHECK_FALSE(hbos::mergeable(p, 5));
    CHECK_THROWS_WITH(hbos::ShardedFit<double>(range, p), Catch::Contains("feature 2"));
  }
}

TEST_CASE("inconsistent shards and summaries are refused", "[merge]") {
  const Eigen::MatrixXd x = mixed_features<double>(2, 100, true);
  const hbos::ShardedFit<double> plan(hbos::summarize_range(x.topRows(50)));
  // A row the range pass did not see.
  CHECK_THROWS_WITH(plan.count(x), Catch::Contains("outside the range"));
  CHECK_THROWS_WITH(plan.count(x.leftCols(3)), Catch::Contains("has 3 columns"));
  const hbos::CountSummary half = plan.count(x.topRows(25));
  CHECK_THROWS_WITH(plan.model(half), Catch::Contains("cover 25 rows but the range summary 50"));
  Eigen::MatrixXd bad = x.topRows(10);
  bad(3, 1) = std::nan("");
  CHECK_THROWS_WITH(hbos::summarize_range(bad), Catch::Contains("X(3, 1)"));
  CHECK_THROWS_WITH(plan.count(bad), Catch::Contains("X(3, 1)"));
  CHECK_THROWS_WITH(hbos::merge(hbos::summarize_range(x), hbos::summarize_range(x.leftCols(2))),
                    Catch::Contains("5 and 2 features"));
  const hbos::ShardedFit<double> other(hbos::summarize_range(x.topRows(50)), [] {
    hbos::HbosParams p;
    p.feature.binning.shifts = 1;
    return p;
  }());
  CHECK_THROWS_WITH(hbos::merge(half, other.count(x.topRows(25))),
                    Catch::Contains("different plans"));
}
