// Tests of hbos/pyod/merge.hpp: a PyOD-mode model fitted on shards is bit-identical to
// PyodHbos::fit on all rows (model-file text, edges, counts, densities, training scores,
// threshold, labels, scores of new data) under any split and merge order, and reproduces PyOD
// 3.6.5's reference vectors; n_bins = auto and inconsistent summaries are refused.

#include <hbos/pyod/merge.hpp>
#include <hbos/pyod/model_file.hpp>

#include "../support/mixed_features.hpp"
#include "../support/shard_merges.hpp"

#include "../support/pyod_vectors.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

// Every member of the class templates compiles for both scalar types.
template class hbos::PyodShardedFit<float>;
template class hbos::PyodShardedFit<double>;
template class hbos::PyodHistograms<float>;
template class hbos::PyodHistograms<double>;

namespace {

using Eigen::Index;
using hbos::test::mixed_features;
using hbos::test::read_csv_matrix;
using hbos::test::read_json_arrays;
using hbos::test::read_vector;
using hbos::test::same_bits;

template <class Scalar>
using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

hbos::PyodParams pyod_params(Index n_bins, double alpha = 0.1, double tol = 0.5,
                             double contamination = 0.1) {
  hbos::PyodParams p;
  p.n_bins = n_bins;
  p.alpha = alpha;
  p.tol = tol;
  p.contamination = contamination;
  return p;
}

/// Row shards of x cut at `cuts` (sorted, from 0 to x.rows()).
template <class Scalar>
std::vector<Matrix<Scalar>> cut(const Matrix<Scalar>& x, std::vector<Index> cuts) {
  return hbos::test::row_shards(x, std::move(cuts));
}

/// The splits every property is checked under: one shard, two uneven ones, random cuts with a
/// one-row shard first and last, and one row per shard.
template <class Scalar>
std::vector<std::pair<std::string, std::vector<Matrix<Scalar>>>> splits(const Matrix<Scalar>& x,
                                                                        std::uint32_t seed) {
  const Index n = x.rows();
  std::vector<std::pair<std::string, std::vector<Matrix<Scalar>>>> out;
  out.emplace_back("one shard", cut(x, {0, n}));
  out.emplace_back("uneven halves", cut(x, {0, n / 7 + 1, n}));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<Index> at(1, n - 1);
  std::vector<Index> cuts = {0, 1, n - 1, n};
  for (int i = 0; i < 9; ++i) cuts.push_back(at(rng));
  out.emplace_back("random cuts with one-row shards", cut(x, cuts));
  std::vector<Index> every(static_cast<std::size_t>(n + 1));
  for (Index i = 0; i <= n; ++i) every[static_cast<std::size_t>(i)] = i;
  out.emplace_back("one row per shard", cut(x, every));
  return out;
}

template <class Scalar>
Matrix<Scalar> stacked(const std::vector<Matrix<Scalar>>& shards) {
  Index rows = 0;
  for (const auto& s : shards) rows += s.rows();
  Matrix<Scalar> x(rows, shards.front().cols());
  Index first = 0;
  for (const auto& s : shards) {
    x.middleRows(first, s.rows()) = s;
    first += s.rows();
  }
  return x;
}

/// Everything a PyOD model holds and computes, compared bit for bit.
template <class Scalar>
void check_same_model(const hbos::PyodHbos<Scalar>& merged, const hbos::PyodHbos<Scalar>& whole,
                      const Matrix<Scalar>& queries) {
  CHECK(hbos::to_model_text(merged) == hbos::to_model_text(whole));
  REQUIRE(merged.n_features() == whole.n_features());
  for (Index j = 0; j < whole.n_features(); ++j) {
    CHECK(same_bits(merged.bin_edges(j), whole.bin_edges(j)));
    CHECK(merged.counts(j) == whole.counts(j));
    CHECK(same_bits(merged.densities(j), whole.densities(j)));
  }
  CHECK(same_bits(merged.decision_scores(), whole.decision_scores()));
  CHECK(same_bits(Eigen::Matrix<Scalar, 1, 1>::Constant(merged.threshold()),
                  Eigen::Matrix<Scalar, 1, 1>::Constant(whole.threshold())));
  CHECK(merged.labels() == whole.labels());
  CHECK(same_bits(merged.decision_function(queries), whole.decision_function(queries)));
  CHECK(merged.predict(queries) == whole.predict(queries));
}

/// Training rows and queries of d features: mixed_features' shapes (a normal, a tail, an
/// integer die whose values sit on interior edges for n_bins 3 and 6, a uniform, a constant),
/// repeated with offsets up to d columns; queries inside, on and beyond the range.
template <class Scalar>
std::pair<Matrix<Scalar>, Matrix<Scalar>> data(std::uint32_t seed, Index n, Index d) {
  const Matrix<Scalar> base = mixed_features<Scalar>(seed, n, true);
  Matrix<Scalar> x(n, d);
  for (Index j = 0; j < d; ++j) {
    x.col(j) = base.col(j % 5).array() + static_cast<Scalar>(j / 5);
  }
  Matrix<Scalar> q(2 * n + 2, d);
  q.topRows(n) = x;
  q.middleRows(n, n) = (x.array() * Scalar(1.3) - Scalar(0.7)).matrix();
  q.row(2 * n) = x.colwise().minCoeff().array() - Scalar(0.01);
  q.row(2 * n + 1) = x.colwise().maxCoeff().array() + Scalar(0.01);
  return {x, q};
}

template <class Scalar>
void check_sharded_equals_whole(std::uint32_t seed, Index n, Index d,
                                const hbos::PyodParams& params) {
  const auto [x, q] = data<Scalar>(seed, n, d);
  for (const auto& [name, shards] : splits(x, seed)) {
    INFO(name << ": " << shards.size() << " shards");
    const auto whole = hbos::PyodHbos<Scalar>::fit(stacked(shards), params);
    check_same_model(hbos::fit_sharded(shards, params), whole, q);

    // The summaries reduce in any order (reversed, a tree) to the same model.
    const auto range = hbos::test::range_merged_in_reverse(shards);
    const hbos::PyodShardedFit<Scalar> plan(range, params);
    const hbos::CountSummary total = hbos::test::counts_merged_as_tree(plan, shards);
    const hbos::PyodHistograms<Scalar> histograms = plan.histograms(total);
    CHECK(histograms.rows() == n);
    CHECK(same_bits(histograms.decision_function(q), whole.decision_function(q)));
    // The scoring pass, shard by shard, gives the training outputs.
    typename hbos::PyodHistograms<Scalar>::Vector scores(n);
    Index first = 0;
    for (const auto& s : shards) {
      scores.segment(first, s.rows()) = histograms.decision_function(s);
      first += s.rows();
    }
    check_same_model(histograms.model(scores), whole, q);
  }
}

}  // namespace

TEST_CASE("pyod: a model fitted on shards is bit-identical to the whole fit", "[pyod][merge]") {
  const std::vector<std::pair<std::string, hbos::PyodParams>> modes = {
      {"PyOD's defaults (10 bins)", pyod_params(10)},
      {"3 bins: the die's values on edges", pyod_params(3)},
      {"6 bins, alpha 0.01, tol 0.2", pyod_params(6, 0.01, 0.2, 0.05)},
      {"37 bins, contamination 0.5", pyod_params(37, 0.3, 0.9, 0.5)}};
  for (const auto& [name, params] : modes) {
    SECTION(name) {
      REQUIRE(hbos::mergeable(params));
      for (std::uint32_t seed = 1; seed <= 3; ++seed) {
        // 1 feature, 5 (one constant), 13 (numpy's pairwise row sum: 8 features or more).
        for (const Index d : {Index{1}, Index{5}, Index{13}}) {
          INFO("seed " << seed << ", " << d << " features");
          check_sharded_equals_whole<double>(seed, 60 + 41 * seed, d, params);
          check_sharded_equals_whole<float>(seed, 60 + 41 * seed, d, params);
        }
      }
    }
  }
  SECTION("more bins than the 16-bit scored-bin store (fit scores like new data)") {
    check_sharded_equals_whole<double>(4, 300, 2, pyod_params(70000));
  }
}

TEST_CASE("pyod: a model fitted on shards reproduces PyOD 3.6.5's reference vectors",
          "[pyod][merge][parity]") {
  const std::string data_dir = std::string(HBOS_TEST_DATA_DIR) + "/hbos_pyod/";
  const std::vector<std::pair<std::string, hbos::PyodParams>> tags = {
      {"nb10_a0.1_tol0.5", pyod_params(10)},
      {"nb5_a0.1_tol0.5", pyod_params(5)},
      {"nb20_a0.01_tol0.2", pyod_params(20, 0.01, 0.2)}};
  for (const std::string name : {"cardio", "pima", "glass", "lympho", "vertebral", "wbc"}) {
    const std::string dir = data_dir + name + "/";
    const Eigen::MatrixXd X = read_csv_matrix(dir + "X.csv");
    const Eigen::MatrixXd X_test = read_csv_matrix(dir + "X_test.csv");
    // Seven uneven shards, a one-row shard among them.
    const Index n = X.rows();
    const auto shards = cut<double>(X, {0, 1, n / 9, n / 3, n / 3 + 1, n / 2, 4 * n / 5, n});
    for (const auto& [tag, params] : tags) {
      INFO(name << " / " << tag);
      const auto merged = hbos::fit_sharded(shards, params);
      const auto edges = read_json_arrays(dir + "edges_" + tag + ".json");
      const auto hist = read_json_arrays(dir + "hist_" + tag + ".json");
      const auto counts = read_json_arrays(dir + "counts_" + tag + ".json");
      REQUIRE(static_cast<Index>(edges.size()) == X.cols());
      Index mismatches = 0;
      for (Index j = 0; j < X.cols(); ++j) {
        const auto uj = static_cast<std::size_t>(j);
        REQUIRE(merged.bins(j) == static_cast<Index>(hist[uj].size()));
        for (Index k = 0; k <= merged.bins(j); ++k)
          mismatches += merged.bin_edges(j)[k] == edges[uj][static_cast<std::size_t>(k)] ? 0 : 1;
        for (Index k = 0; k < merged.bins(j); ++k) {
          mismatches += merged.densities(j)[k] == hist[uj][static_cast<std::size_t>(k)] ? 0 : 1;
          mismatches +=
              static_cast<double>(merged.counts(j)[k]) == counts[uj][static_cast<std::size_t>(k)]
                  ? 0
                  : 1;
        }
      }
      CHECK(mismatches == 0);
      // Scores, scores of new data and threshold: PyOD's bits (integer n_bins).
      CHECK(merged.decision_scores() == read_vector(dir + "scores_" + tag + ".csv"));
      CHECK(merged.decision_function(X_test) == read_vector(dir + "test_scores_" + tag + ".csv"));
      CHECK(merged.threshold() == read_vector(dir + "threshold_" + tag + ".txt")[0]);
      CHECK(merged.labels() == read_vector(dir + "labels_" + tag + ".csv").cast<int>());
      check_same_model(merged, hbos::PyodHbosd::fit(X, params), X_test);
    }
  }
}

TEST_CASE("pyod: shards are counted with numpy's edges of the merged range", "[pyod][merge]") {
  // Values placed exactly on numpy's edges of [0.1, 0.3] with 10 bins: numpy's linspace edges
  // (k * step, rounded, + lo) differ in the last bit from lo + k (hi - lo) / B and from
  // lo (1 - k/B) + hi k/B at several k, so a value there lands in a different bin under those
  // formulas: a plan that placed its edges any other way would count, and score, differently.
  const double lo = 0.1;
  const double hi = 0.3;
  const Index B = 10;
  Eigen::VectorXd numpy_edges(B + 1);
  hbos::detail::numpy_histogram_edges({lo, hi}, B, numpy_edges.data());
  Index differs_a = 0;
  Index differs_b = 0;
  for (Index k = 1; k < B; ++k) {
    const double t = static_cast<double>(k) / static_cast<double>(B);
    differs_a +=
        lo + static_cast<double>(k) * (hi - lo) / static_cast<double>(B) != numpy_edges[k] ? 1 : 0;
    differs_b += lo * (1.0 - t) + hi * t != numpy_edges[k] ? 1 : 0;
  }
  // The data below can tell numpy's formula from both others (3 and 5 edges differ).
  REQUIRE(differs_a >= 1);
  REQUIRE(differs_b >= 1);

  // Each edge (and its neighbours one ULP away) several times, in the second column a constant
  // (numpy widens its range by 0.5 each side), spread over shards none of which sees the range.
  std::vector<double> values;
  for (Index k = 0; k <= B; ++k) {
    for (int r = 0; r < 3 + static_cast<int>(k % 4); ++r) values.push_back(numpy_edges[k]);
    if (k > 0) values.push_back(std::nextafter(numpy_edges[k], lo));
    if (k < B) values.push_back(std::nextafter(numpy_edges[k], hi));
  }
  const auto n = static_cast<Index>(values.size());
  Eigen::MatrixXd x(n, 2);
  for (Index i = 0; i < n; ++i) {
    x(i, 0) = values[static_cast<std::size_t>((i * 7) % n)];  // 7 is prime to n: a permutation
    x(i, 1) = -3.0;
  }
  REQUIRE(std::gcd(n, Index{7}) == 1);
  const auto whole = hbos::PyodHbosd::fit(x, pyod_params(B));
  REQUIRE(same_bits(whole.bin_edges(0), numpy_edges));
  const auto shards = cut<double>(x, {0, 5, 6, n / 2, n - 1, n});
  hbos::RangeSummary<double> range;
  for (const auto& s : shards) range = hbos::merge(range, hbos::summarize_range(s));
  const hbos::PyodShardedFit<double> plan(range, pyod_params(B));
  CHECK(same_bits(plan.bin_edges(0), numpy_edges));
  CHECK(plan.bin_edges(1)[0] == -3.5);
  CHECK(plan.bin_edges(1)[B] == -2.5);
  hbos::CountSummary total;
  for (const auto& s : shards) total = hbos::merge(total, plan.count(s));
  for (Index j = 0; j < 2; ++j) {
    const auto& c = total.counts[static_cast<std::size_t>(j)];
    CHECK(Eigen::Map<const hbos::PyodHbosd::Counts>(c.data(), B) == whole.counts(j));
  }
  const auto merged = hbos::fit_sharded(shards, pyod_params(B));
  Eigen::MatrixXd q(n + 2, 2);
  q << x, Eigen::RowVector2d(lo - 0.03, -3.6), Eigen::RowVector2d(hi + 0.01, -2.0);
  check_same_model(merged, whole, q);
}

TEST_CASE("pyod: n_bins = auto cannot be fitted by shards, and says why", "[pyod][merge]") {
  const Eigen::MatrixXd x = mixed_features<double>(1, 100, true);
  hbos::PyodParams p;
  p.auto_bins = true;
  CHECK_FALSE(hbos::mergeable(p));
  CHECK_THROWS_WITH(hbos::PyodShardedFit<double>(hbos::summarize_range(x), p),
                    Catch::Contains("n_bins = auto cannot be fitted by shards") &&
                        Catch::Contains("Birge-Rozenblac") && Catch::Contains("integer n_bins"));
  CHECK_THROWS_AS(hbos::fit_sharded(std::vector<Eigen::MatrixXd>{x}, p), hbos::InvalidArgument);
  // PyOD's own parameter checks apply as in fit.
  CHECK_THROWS_WITH(hbos::PyodShardedFit<double>(hbos::summarize_range(x), pyod_params(2)),
                    Catch::Contains("n_bins must be > 2"));
  CHECK_THROWS_WITH(hbos::PyodShardedFit<double>(hbos::summarize_range(x), pyod_params(10, 1.5)),
                    Catch::Contains("alpha"));
}

TEST_CASE("pyod: inconsistent shards and summaries are refused", "[pyod][merge]") {
  const Eigen::MatrixXd x = mixed_features<double>(2, 100, true);
  const hbos::PyodShardedFit<double> plan(hbos::summarize_range(x.topRows(50)), pyod_params(10));
  CHECK(plan.rows() == 50);
  CHECK(plan.n_features() == 5);
  CHECK_THROWS_WITH(plan.count(x), Catch::Contains("outside the range"));
  CHECK_THROWS_WITH(plan.count(x.leftCols(3)), Catch::Contains("has 3 columns"));
  const hbos::CountSummary half = plan.count(x.topRows(25));
  CHECK_THROWS_WITH(plan.histograms(half),
                    Catch::Contains("cover 25 rows but the range summary 50"));
  hbos::CountSummary forged = hbos::merge(half, plan.count(x.middleRows(25, 25)));
  forged.counts[2][0] += 1;
  CHECK_THROWS_WITH(plan.histograms(forged), Catch::Contains("feature 2: the counts add up to 51"));
  forged.counts[2].pop_back();
  CHECK_THROWS_WITH(plan.histograms(forged), Catch::Contains("feature 2: 9 counts"));
  Eigen::MatrixXd bad = x.topRows(10);
  bad(3, 1) = std::nan("");
  CHECK_THROWS_WITH(plan.count(bad), Catch::Contains("X(3, 1)"));
  const hbos::CountSummary total = hbos::merge(half, plan.count(x.middleRows(25, 25)));
  const hbos::PyodHistograms<double> histograms = plan.histograms(total);
  CHECK_THROWS_WITH(histograms.model(Eigen::VectorXd::Zero(49)),
                    Catch::Contains("50 rows but 49 training scores"));
  Eigen::VectorXd scores = histograms.decision_function(x.topRows(50));
  scores[7] = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(histograms.model(scores), Catch::Contains("training score 7"));
  // Counts of another plan (another n_bins) do not merge.
  const hbos::PyodShardedFit<double> other(hbos::summarize_range(x.topRows(50)), pyod_params(12));
  CHECK_THROWS_WITH(hbos::merge(half, other.count(x.topRows(25))),
                    Catch::Contains("different plans"));
  // A range whose width overflows a double, as fit refuses it.
  Eigen::MatrixXd huge(2, 1);
  huge << -1.5e308, 1.5e308;
  CHECK_THROWS_WITH(hbos::PyodShardedFit<double>(hbos::summarize_range(huge), pyod_params(10)),
                    Catch::Contains("overflows a double"));
}
