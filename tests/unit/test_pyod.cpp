// Tests of hbos/pyod.hpp: parity with PyOD 3.6.5's HBOS on the reference vectors in
// tests/data/hbos_pyod (six ODDS sets x four parameter tags), input layouts, float vs double,
// bad input, and the two PyOD defects docs/pyod_compat.md quotes.

#include <hbos/model.hpp>
#include <hbos/pyod.hpp>

#include "../support/pyod_vectors.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

// Every member of both instantiations must compile.
template class hbos::PyodHbos<double>;
template class hbos::PyodHbos<float>;

namespace {

using Eigen::Index;
using hbos::test::numbers_in;
using hbos::test::read_csv_matrix;
using hbos::test::read_json_arrays;
using hbos::test::read_text;
using hbos::test::read_vector;
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

const std::string kDataDir = std::string(HBOS_TEST_DATA_DIR) + "/hbos_pyod/";
const std::vector<std::string> kDatasets = {"cardio", "pima",      "glass",
                                            "lympho", "vertebral", "wbc"};

struct Tag {
  std::string name;
  hbos::PyodParams params;
};

std::vector<Tag> tags() {
  std::vector<Tag> out(4);
  out[0].name = "nb10_a0.1_tol0.5";
  out[1].name = "nb5_a0.1_tol0.5";
  out[1].params.n_bins = 5;
  out[2].name = "nb20_a0.01_tol0.2";
  out[2].params.n_bins = 20;
  out[2].params.alpha = 0.01;
  out[2].params.tol = 0.2;
  out[3].name = "nbauto_a0.1_tol0.5";
  out[3].params.auto_bins = true;
  return out;
}

/// meta.json -> params -> tag -> section -> key (an integer), by plain text search.
Index meta_count(const std::string& meta, const std::string& tag, const std::string& section,
                 const std::string& key) {
  std::size_t pos = meta.find("\"" + tag + "\"");
  REQUIRE(pos != std::string::npos);
  pos = meta.find("\"" + section + "\"", pos);
  REQUIRE(pos != std::string::npos);
  pos = meta.find("\"" + key + "\"", pos);
  REQUIRE(pos != std::string::npos);
  return std::strtol(meta.c_str() + meta.find(':', pos) + 1, nullptr, 10);
}

/// Largest |c - r| / max(1, |r|): the README's pass criterion is <= 1e-9.
double max_rel_deviation(const Eigen::VectorXd& computed, const Eigen::VectorXd& reference) {
  REQUIRE(computed.size() == reference.size());
  double worst = 0.0;
  for (Index i = 0; i < computed.size(); ++i) {
    worst = std::max(worst,
                     std::abs(computed[i] - reference[i]) / std::max(1.0, std::abs(reference[i])));
  }
  return worst;
}

/// ROC-AUC (Mann-Whitney, ties count one half), as sklearn's roc_auc_score.
double roc_auc(const Eigen::VectorXd& scores, const Eigen::VectorXd& y) {
  const Index n = scores.size();
  std::vector<Index> order(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) order[static_cast<std::size_t>(i)] = i;
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return scores[a] < scores[b]; });
  double rank_sum = 0.0;  // sum of the (tie-averaged, 1-based) ranks of the positives
  for (Index i = 0; i < n;) {
    Index k = i;
    while (k < n && scores[order[static_cast<std::size_t>(k)]] ==
                        scores[order[static_cast<std::size_t>(i)]]) {
      ++k;
    }
    const double mid_rank = 0.5 * static_cast<double>(i + 1 + k);
    for (Index t = i; t < k; ++t) rank_sum += y[order[static_cast<std::size_t>(t)]] * mid_rank;
    i = k;
  }
  const double positives = y.sum();
  const double negatives = static_cast<double>(n) - positives;
  return (rank_sum - positives * (positives + 1.0) / 2.0) / (positives * negatives);
}

const char* branch_name(hbos::PyodBranch b) {
  switch (b) {
    case hbos::PyodBranch::InRange:
      return "in_range";
    case hbos::PyodBranch::BelowWithinTol:
      return "below_within_tol";
    case hbos::PyodBranch::BelowBeyondTol:
      return "below_beyond_tol";
    case hbos::PyodBranch::AboveWithinTol:
      return "above_within_tol";
    case hbos::PyodBranch::AboveBeyondTol:
      return "above_beyond_tol";
  }
  return "?";
}

/// How many (row, feature) values take each branch, in meta.json's vocabulary.
std::vector<std::pair<std::string, Index>> branch_counts(const hbos::PyodHbosd& model,
                                                         const Eigen::MatrixXd& X) {
  std::vector<std::pair<std::string, Index>> counts = {
      {"in_range", 0},         {"on_interior_edge", 0}, {"below_within_tol", 0},
      {"below_beyond_tol", 0}, {"above_within_tol", 0}, {"above_beyond_tol", 0}};
  for (Index j = 0; j < X.cols(); ++j) {
    for (Index i = 0; i < X.rows(); ++i) {
      const hbos::PyodLookup l = model.lookup(j, X(i, j));
      for (auto& c : counts) c.second += c.first == branch_name(l.branch) ? 1 : 0;
      counts[1].second += l.on_interior_edge ? 1 : 0;
    }
  }
  return counts;
}

Eigen::MatrixXd standard_normal(Index rows, Index cols, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd X(rows, cols);
  for (Index j = 0; j < cols; ++j) {
    for (Index i = 0; i < rows; ++i) X(i, j) = normal(rng);
  }
  return X;
}

}  // namespace

TEST_CASE("pyod: every ODDS set and parameter tag reproduces PyOD 3.6.5", "[pyod][parity]") {
  for (const std::string& name : kDatasets) {
    const std::string dir = kDataDir + name + "/";
    const Eigen::MatrixXd X = read_csv_matrix(dir + "X.csv");
    const Eigen::MatrixXd X_test = read_csv_matrix(dir + "X_test.csv");
    const std::string meta = read_text(dir + "meta.json");
    REQUIRE(X_test.rows() == X.rows() + 9);
    for (const Tag& tag : tags()) {
      INFO(name << " / " << tag.name);
      const auto model = hbos::PyodHbosd::fit(X, tag.params);
      const auto edges = read_json_arrays(dir + "edges_" + tag.name + ".json");
      const auto hist = read_json_arrays(dir + "hist_" + tag.name + ".json");
      const auto counts = read_json_arrays(dir + "counts_" + tag.name + ".json");
      REQUIRE(static_cast<Index>(edges.size()) == X.cols());
      REQUIRE(model.n_features() == X.cols());
      REQUIRE(model.n_samples() == X.rows());

      // Bin counts, edges, densities and counts: identical.
      Index edge_mismatches = 0;
      Index density_mismatches = 0;
      Index count_mismatches = 0;
      for (Index j = 0; j < X.cols(); ++j) {
        const auto& e = edges[static_cast<std::size_t>(j)];
        const auto& h = hist[static_cast<std::size_t>(j)];
        const auto& c = counts[static_cast<std::size_t>(j)];
        INFO("feature " << j);
        REQUIRE(model.bins(j) == static_cast<Index>(h.size()));
        REQUIRE(model.bin_edges(j).size() == static_cast<Index>(e.size()));
        for (Index k = 0; k <= model.bins(j); ++k) {
          edge_mismatches += model.bin_edges(j)[k] == e[static_cast<std::size_t>(k)] ? 0 : 1;
        }
        for (Index k = 0; k < model.bins(j); ++k) {
          density_mismatches += model.densities(j)[k] == h[static_cast<std::size_t>(k)] ? 0 : 1;
          count_mismatches +=
              static_cast<double>(model.counts(j)[k]) == c[static_cast<std::size_t>(k)] ? 0 : 1;
        }
        CHECK(model.counts(j).sum() == X.rows());
      }
      CHECK(edge_mismatches == 0);
      CHECK(density_mismatches == 0);
      CHECK(count_mismatches == 0);

      // Scores, test scores and threshold: within 1e-9 relative (max(1, |r|)).
      const Eigen::VectorXd scores = read_vector(dir + "scores_" + tag.name + ".csv");
      const Eigen::VectorXd test_scores = read_vector(dir + "test_scores_" + tag.name + ".csv");
      const double threshold = read_vector(dir + "threshold_" + tag.name + ".txt")[0];
      CHECK(max_rel_deviation(model.decision_scores(), scores) <= 1e-9);
      CHECK(max_rel_deviation(model.decision_function(X_test), test_scores) <= 1e-9);
      CHECK(std::abs(model.threshold() - threshold) <= 1e-9 * std::max(1.0, std::abs(threshold)));
      // PyOD checks this bit for bit while generating the vectors; so do we.
      CHECK(model.decision_function(X) == model.decision_scores());

      // Labels: identical.
      const Eigen::VectorXd labels = read_vector(dir + "labels_" + tag.name + ".csv");
      CHECK(model.labels() == labels.cast<int>());
      CHECK(model.predict(X) == model.labels());

      // Branch choices: the same number of values take each scoring branch as in PyOD.
      for (const auto& [section, data] : {std::make_pair(std::string("branches_train"), &X),
                                          std::make_pair(std::string("branches_test"), &X_test)}) {
        for (const auto& [key, count] : branch_counts(model, *data)) {
          INFO(section << "." << key);
          CHECK(count == meta_count(meta, tag.name, section, key));
        }
      }
    }
  }
}

TEST_CASE("pyod: per-value trace on vertebral matches PyOD's branch, bin and log term",
          "[pyod][parity]") {
  const std::string dir = kDataDir + "vertebral/";
  const auto model = hbos::PyodHbosd::fit(read_csv_matrix(dir + "X.csv"));
  std::ifstream in(dir + "trace_test_nb10_a0.1_tol0.5.csv");
  REQUIRE(in);
  std::string line;
  std::getline(in, line);  // header: row,feature,x,digitize_right,branch,bin_used,log2_...
  Index rows = 0;
  Index mismatches = 0;
  double worst_term = 0.0;
  while (std::getline(in, line)) {
    std::vector<std::string> field;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');) field.push_back(f);
    REQUIRE(field.size() == 7);
    const Index j = std::stol(field[1]);
    const hbos::PyodLookup l = model.lookup(j, std::strtod(field[2].c_str(), nullptr));
    const bool same = field[4] == branch_name(l.branch) && std::stol(field[5]) == l.bin;
    if (!same) UNSCOPED_INFO("trace line " << rows << ": " << line);
    mismatches += same ? 0 : 1;
    const double reference = std::strtod(field[6].c_str(), nullptr);
    worst_term = std::max(worst_term, std::abs(l.log_term - reference) / std::abs(reference));
    ++rows;
  }
  CHECK(rows == 249 * 6);
  CHECK(mismatches == 0);
  CHECK(worst_term <= 1e-12);
}

TEST_CASE("pyod: ROC-AUC of the reproduced scores equals auc.csv", "[pyod][parity]") {
  const std::string text = read_text(kDataDir + "auc.csv");
  std::stringstream lines(text);
  std::string line;
  std::getline(lines, line);  // header
  Index checked = 0;
  while (std::getline(lines, line)) {
    const std::string name = line.substr(0, line.find(','));
    const std::vector<double> values = numbers_in(line.substr(line.find(',')));
    REQUIRE(values.size() == 8);  // n, d, outliers, default, then one per tag
    const Eigen::MatrixXd X = read_csv_matrix(kDataDir + name + "/X.csv");
    const Eigen::VectorXd y = read_vector(kDataDir + name + "/y.csv");
    const auto all_tags = tags();
    for (std::size_t t = 0; t < all_tags.size(); ++t) {
      INFO(name << " / " << all_tags[t].name);
      const auto model = hbos::PyodHbosd::fit(X, all_tags[t].params);
      CHECK(roc_auc(model.decision_scores(), y) == Approx(values[4 + t]).epsilon(1e-12));
    }
    ++checked;
  }
  CHECK(checked == 6);
}

TEST_CASE("pyod: scoring and counting equal the edge-by-edge definition", "[pyod]") {
  // The look-up grid must give exactly what digitize + PyOD's branches give (lookup() takes that
  // general path), and the counts exactly the edge rule, also with many values on edges, values
  // outside the range, and bin counts large enough that cells hold several edges.
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> integer(0, 40);
  const Index n = 20000;
  Eigen::MatrixXd X(n, 3);
  for (Index i = 0; i < n; ++i) {
    X(i, 0) = normal(rng);
    X(i, 1) = integer(rng);                 // on interior edges for many B
    X(i, 2) = std::exp(3.0 * normal(rng));  // heavy right tail
  }
  Eigen::MatrixXd X_new = X * 1.3;
  X_new.col(1).array() -= 3.0;
  // 40000 bins: cells hold several edges; 70000: training values are scored like new data.
  for (const Index bins :
       {Index{3}, Index{10}, Index{40}, Index{2000}, Index{40000}, Index{70000}}) {
    INFO("n_bins " << bins);
    hbos::PyodParams params;
    params.n_bins = bins;
    const auto model = hbos::PyodHbosd::fit(X, params);
    for (Index j = 0; j < X.cols(); ++j) {
      const Eigen::VectorXd& e = model.bin_edges(j);
      hbos::PyodHbosd::Counts expected = hbos::PyodHbosd::Counts::Zero(bins);
      for (Index i = 0; i < n; ++i) {
        // e_k <= x < e_{k+1}, the last bin closed.
        const auto k = std::upper_bound(e.data(), e.data() + bins + 1, X(i, j)) - e.data() - 1;
        ++expected[std::min<Index>(k, bins - 1)];
      }
      CHECK(model.counts(j) == expected);
    }
    CHECK(model.decision_function(X) == model.decision_scores());
    for (const Eigen::MatrixXd* data : {&X, &X_new}) {
      const Eigen::VectorXd scores = model.decision_function(*data);
      Index mismatches = 0;
      for (Index i = 0; i < data->rows(); ++i) {
        double sum = 0.0;  // numpy's pairwise sum of 3 terms is the plain loop
        for (Index j = 0; j < data->cols(); ++j) sum += model.lookup(j, (*data)(i, j)).log_term;
        mismatches += scores[i] == -sum ? 0 : 1;
      }
      CHECK(mismatches == 0);
    }
  }
}

namespace {

/// Checks a feature fitted on its own (PyodFeatureModel, with or without a look-up grid) against
/// the same column fitted as a one-feature PyodHbos (always with its grid), bit for bit: the
/// histogram, the training terms, the terms of new values and the feature rebuilt from its parts.
template <class Scalar>
void check_feature_without_grid(const std::vector<Scalar>& column, const std::vector<Scalar>& probe,
                                const hbos::PyodParams& params) {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  const auto n = static_cast<Index>(column.size());
  const auto m = static_cast<Index>(probe.size());
  const Eigen::Map<const Vector> x(column.data(), n);
  const Eigen::Map<const Vector> x_new(probe.data(), m);
  const auto whole = hbos::PyodHbos<Scalar>::fit(x, params);

  std::vector<double> terms(column.size());
  const auto f = hbos::PyodFeatureModel<Scalar>::fit(column.data(), 1, n, 0, params, terms.data());
  const Index boundary = hbos::PyodFeatureModel<Scalar>::grid_min_samples(f.bins());
  INFO("n " << n << ", bins " << f.bins() << ", grid from " << boundary << " samples");
  CHECK(f.has_lookup_grid() == (n >= boundary));
  CHECK(f.bin_edges() == whole.bin_edges(0));
  CHECK(f.counts() == whole.counts(0));
  CHECK(f.densities() == whole.densities(0));
  // A one-feature score is -(0 + term): the training terms must be decision_scores() negated.
  Index mismatches = 0;
  for (Index i = 0; i < n; ++i) {
    const auto score = static_cast<Scalar>(-terms[static_cast<std::size_t>(i)]);
    mismatches += std::memcmp(&score, &whole.decision_scores()[i], sizeof(Scalar)) == 0 ? 0 : 1;
  }
  CHECK(mismatches == 0);

  // New values: in range, on edges, and outside it within and beyond tol.
  const Vector expected = whole.decision_function(x_new);
  auto check_terms = [&](const hbos::PyodFeatureModel<Scalar>& g) {
    std::vector<double> t(probe.size());
    g.log_terms(probe.data(), 1, m, t.data());
    Index wrong = 0;
    for (Index i = 0; i < m; ++i) {
      const auto score = static_cast<Scalar>(-t[static_cast<std::size_t>(i)]);
      wrong += std::memcmp(&score, &expected[i], sizeof(Scalar)) == 0 ? 0 : 1;
      wrong += t[static_cast<std::size_t>(i)] ==
                       whole.lookup(0, probe[static_cast<std::size_t>(i)]).log_term
                   ? 0
                   : 1;
    }
    CHECK(wrong == 0);
  };
  check_terms(f);
  const auto rebuilt =
      hbos::PyodFeatureModel<Scalar>::from_parts(f.bin_edges(), f.counts(), n, 0, params);
  CHECK(rebuilt.has_lookup_grid() == f.has_lookup_grid());
  CHECK(rebuilt.densities() == whole.densities(0));
  check_terms(rebuilt);
  // A whole model assembled from the feature gets the grid back and scores the same.
  std::vector<hbos::PyodFeatureModel<Scalar>> features{f};
  const auto assembled = hbos::PyodHbos<Scalar>::from_features(std::move(features), params,
                                                               Vector(whole.decision_scores()));
  const Vector again = assembled.decision_function(x_new);
  CHECK(std::memcmp(again.data(), expected.data(), sizeof(Scalar) * static_cast<std::size_t>(m)) ==
        0);
}

template <class Scalar>
void check_grid_boundary() {
  std::mt19937_64 rng(23);
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> integer(0, 40);
  // Integers in [0, 40] sit on interior edges for most B (counted in the bin above, scored with
  // the one below); the normal and heavy-tailed columns cover uneven bins.
  for (const Index bins : {Index{3}, Index{10}, Index{40}, Index{2000}, Index{40000}, Index{0}}) {
    hbos::PyodParams params;
    params.auto_bins = bins == 0;
    params.n_bins = bins == 0 ? 10 : bins;
    const Index boundary = hbos::PyodFeatureModel<Scalar>::grid_min_samples(params.n_bins);
    for (const Index n : {Index{2}, Index{5}, boundary - 1, boundary, boundary + 1}) {
      for (int kind = 0; kind < 3; ++kind) {
        INFO("n_bins " << (bins == 0 ? "auto" : std::to_string(bins)) << ", kind " << kind);
        if (params.auto_bins && n <= 3) continue;
        std::vector<Scalar> column(static_cast<std::size_t>(n));
        for (Scalar& v : column) {
          const double x = kind == 0   ? integer(rng)
                           : kind == 1 ? normal(rng)
                                       : std::exp(3 * normal(rng));
          v = static_cast<Scalar>(x);
        }
        std::vector<Scalar> probe(column);
        const auto [lo, hi] = std::minmax_element(column.begin(), column.end());
        const double width = (static_cast<double>(*hi) - static_cast<double>(*lo)) / 10.0;
        for (const double offset : {0.1, 0.3, 0.49, 0.51, 0.7, 2.0, 100.0}) {
          probe.push_back(static_cast<Scalar>(static_cast<double>(*lo) - offset * width));
          probe.push_back(static_cast<Scalar>(static_cast<double>(*hi) + offset * width));
        }
        for (Scalar& v : column) probe.push_back(static_cast<Scalar>(v * Scalar(1.3) - Scalar(3)));
        check_feature_without_grid<Scalar>(column, probe, params);
      }
    }
  }
}

}  // namespace

TEST_CASE("pyod: a feature fitted without its look-up grid scores bit for bit like one with it",
          "[pyod]") {
  // PyodFeatureModel skips the grid below grid_min_samples(B) samples and finds each value's bin
  // by search; both sides of that boundary must give the whole model's counts and terms.
  check_grid_boundary<double>();
  check_grid_boundary<float>();
}

TEST_CASE("pyod: the sampled percentile equals numpy's, ties and adversarial orders included",
          "[pyod][detail]") {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> normal;
  const Index n = 300001;
  std::vector<std::vector<double>> inputs;
  std::vector<double> v(static_cast<std::size_t>(n));
  for (auto& x : v) x = normal(rng);
  inputs.push_back(v);                                  // continuous
  for (auto& x : v) x = std::round(3.0 * normal(rng));  // ~20 distinct values, heavy ties
  inputs.push_back(v);
  std::sort(v.begin(), v.end());
  inputs.push_back(v);  // sorted
  std::reverse(v.begin(), v.end());
  inputs.push_back(v);                                    // reversed
  inputs.emplace_back(static_cast<std::size_t>(n), 2.5);  // constant
  // Adversarial for the sample (every (n / 4096)-th value): sampled values all 0, the rest not.
  const Index stride = n / 4096;
  for (Index i = 0; i < n; ++i) {
    v[static_cast<std::size_t>(i)] = i % stride == 0 ? 0.0 : 1.0 + std::abs(normal(rng));
  }
  inputs.push_back(v);
  std::vector<double> scratch;
  for (std::size_t t = 0; t < inputs.size(); ++t) {
    for (const double c : {0.1, 0.5, 0.37, 0.001, 1e-6}) {
      INFO("input " << t << ", contamination " << c);
      const auto& in = inputs[t];
      std::vector<double> copy = in;
      const double q = (100.0 * (1.0 - c)) / 100.0;
      const double expected =
          hbos::detail::numpy_percentile_linear(copy.data(), copy.data() + copy.size(), q);
      CHECK(hbos::detail::pyod_threshold(in.data(), n, c, scratch) == expected);
    }
  }
}

TEST_CASE("pyod: the bucketed column counts exactly, whatever the distribution", "[pyod][detail]") {
  std::mt19937_64 rng(13);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const Index n = 50000;
  std::vector<std::vector<double>> columns(4, std::vector<double>(static_cast<std::size_t>(n)));
  for (Index i = 0; i < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    columns[0][u] = normal(rng);
    columns[1][u] = std::floor(4.0 * normal(rng));             // ties
    columns[2][u] = 1.0 / (uniform(rng) + 1e-12) - 1.0;        // one cell holds almost everything
    columns[3][u] = i % 1000 == 0 ? 1e6 : normal(rng) * 1e-3;  // a far group and a tight one
  }
  hbos::detail::BucketedColumn<double> bucketed;
  for (std::size_t t = 0; t < columns.size(); ++t) {
    INFO("column " << t);
    const auto& col = columns[t];
    const auto [lo, hi] = std::minmax_element(col.begin(), col.end());
    bucketed.reset(col.data(), 1, n, *lo, *hi);
    std::vector<double> sorted = col;
    std::sort(sorted.begin(), sorted.end());
    std::vector<double> queries = {*lo - 1.0, *lo, *hi, *hi + 1.0, 0.0, -0.0};
    for (Index q = 0; q < 2000; ++q) {
      queries.push_back(col[static_cast<std::size_t>(q * 7)]);                 // values themselves
      queries.push_back(*lo + (*hi - *lo) * static_cast<double>(q) / 2000.0);  // a grid
      queries.push_back(std::nextafter(col[static_cast<std::size_t>(q * 11)], -1e300));
    }
    Index mismatches = 0;
    for (const double e : queries) {
      const auto expected = std::lower_bound(sorted.begin(), sorted.end(), e) - sorted.begin();
      mismatches += bucketed.count_below(e) == expected ? 0 : 1;
    }
    CHECK(mismatches == 0);
  }
}

TEST_CASE("pyod: auto bins equal a direct evaluation of PyOD's formula", "[pyod][detail]") {
  // Reference: for every b, count each bin by testing every value against its edges, then the
  // README's L(b) with numpy's rounding; the fast search must pick the same b.
  auto reference = [](const std::vector<double>& x) {
    const Index n = static_cast<Index>(x.size());
    const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
    const hbos::detail::OuterEdges range = hbos::detail::numpy_outer_edges(*lo, *hi);
    const auto upper = static_cast<Index>(std::sqrt(static_cast<double>(n)));
    Index best_bins = 1;
    double best = -std::numeric_limits<double>::infinity();
    for (Index b = 1; b < upper; ++b) {
      std::vector<double> e(static_cast<std::size_t>(b + 1));
      hbos::detail::numpy_histogram_edges(range, b, e.data());
      std::vector<Index> count(static_cast<std::size_t>(b), 0);
      for (const double v : x) {
        for (Index k = 0; k < b; ++k) {
          const bool last = k == b - 1;
          if (e[static_cast<std::size_t>(k)] <= v &&
              (v < e[static_cast<std::size_t>(k + 1)] || (last && v <= e.back()))) {
            ++count[static_cast<std::size_t>(k)];
            break;
          }
        }
      }
      const double penalty =
          static_cast<double>(b - 1) + std::pow(std::log(static_cast<double>(b)), 2.5);
      std::vector<double> terms;
      for (const Index c : count) {
        const double w = static_cast<double>(c) *
                         std::log(static_cast<double>(b * c) / static_cast<double>(n) + 1.0);
        terms.push_back(w - penalty);
      }
      const double L = hbos::detail::numpy_pairwise_sum(terms.data(), b, 1);
      if (L > best) {
        best = L;
        best_bins = b;
      }
    }
    return best_bins;
  };
  std::mt19937_64 rng(21);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const Index n = 3000;
  std::vector<std::vector<double>> columns;
  std::vector<double> x(static_cast<std::size_t>(n));
  for (auto& v : x) v = normal(rng);
  columns.push_back(x);
  for (auto& v : x) v = std::round(2.0 * normal(rng));
  columns.push_back(x);
  for (auto& v : x) v = uniform(rng) < 0.5 ? normal(rng) : 6.0 + 0.3 * normal(rng);  // bimodal
  columns.push_back(x);
  for (auto& v : x) v = std::exp(2.0 * normal(rng));
  columns.push_back(x);
  hbos::detail::AutoBinsScratch<double> scratch;
  for (std::size_t t = 0; t < columns.size(); ++t) {
    INFO("column " << t);
    const auto& col = columns[t];
    const auto [lo, hi] = std::minmax_element(col.begin(), col.end());
    CHECK(hbos::detail::pyod_optimal_bins(col.data(), 1, n, *lo, *hi, scratch) == reference(col));
  }
}

TEST_CASE("pyod: every input layout gives bit-identical results", "[pyod]") {
  const Eigen::MatrixXd X = standard_normal(500, 3, 7);
  const Eigen::MatrixXd X_new = standard_normal(100, 3, 8) * 1.5;
  for (const bool auto_bins : {false, true}) {
    hbos::PyodParams params;
    params.auto_bins = auto_bins;
    const auto reference = hbos::PyodHbosd::fit(X, params);
    const Eigen::VectorXd expected = reference.decision_function(X_new);
    INFO("auto_bins " << auto_bins);

    const RowMajorMatrix row_major = X;
    const RowMajorMatrix row_major_new = X_new;
    const auto from_buffer = hbos::PyodHbosd::fit(row_major.data(), X.rows(), X.cols(), params);
    CHECK(from_buffer.decision_scores() == reference.decision_scores());
    CHECK(from_buffer.threshold() == reference.threshold());
    CHECK(from_buffer.decision_function(row_major_new.data(), X_new.rows(), X_new.cols()) ==
          expected);
    CHECK(from_buffer.predict(row_major_new.data(), X_new.rows(), X_new.cols()) ==
          reference.predict(X_new));
    CHECK(reference.decision_function(row_major_new.data(), X_new.rows(), X_new.cols()) ==
          expected);

    CHECK(hbos::PyodHbosd::fit(row_major, params).decision_scores() == reference.decision_scores());
    const Eigen::Map<const RowMajorMatrix> map(row_major.data(), X.rows(), X.cols());
    CHECK(hbos::PyodHbosd::fit(map, params).decision_scores() == reference.decision_scores());
    CHECK(reference.decision_function(map) == reference.decision_scores());

    // A block of a wider matrix (outer stride != rows) and a transposed view: no copy needed.
    Eigen::MatrixXd wide = Eigen::MatrixXd::Zero(X.rows() + 4, X.cols() + 2);
    wide.block(2, 1, X.rows(), X.cols()) = X;
    CHECK(hbos::PyodHbosd::fit(wide.block(2, 1, X.rows(), X.cols()), params).decision_scores() ==
          reference.decision_scores());
    const Eigen::MatrixXd Xt = X.transpose();
    CHECK(hbos::PyodHbosd::fit(Xt.transpose(), params).decision_scores() ==
          reference.decision_scores());
    // A non-direct-access expression is evaluated once.
    CHECK(hbos::PyodHbosd::fit(X * 1.0, params).decision_scores() == reference.decision_scores());
    CHECK(reference.decision_function(X_new.array().matrix() + Eigen::MatrixXd::Zero(100, 3)) ==
          expected);
  }
}

TEST_CASE("pyod: a float model is the double model of the same values", "[pyod]") {
  const Eigen::MatrixXf Xf = standard_normal(2000, 4, 11).cast<float>();
  const Eigen::MatrixXf Xf_new = (standard_normal(300, 4, 12) * 2.0).cast<float>();
  const Eigen::MatrixXd Xd = Xf.cast<double>();
  for (const bool auto_bins : {false, true}) {
    INFO("auto_bins " << auto_bins);
    hbos::PyodParams params;
    params.auto_bins = auto_bins;
    const auto mf = hbos::PyodHbosf::fit(Xf, params);
    const auto md = hbos::PyodHbosd::fit(Xd, params);
    for (Index j = 0; j < Xf.cols(); ++j) {
      CHECK(mf.bins(j) == md.bins(j));
      CHECK(mf.bin_edges(j) == md.bin_edges(j));
      CHECK(mf.counts(j) == md.counts(j));
      CHECK(mf.densities(j) == md.densities(j));
    }
    // Scores are the double scores rounded once to float.
    CHECK(mf.decision_scores() == md.decision_scores().cast<float>());
    CHECK(mf.decision_function(Xf_new) ==
          md.decision_function(Xf_new.cast<double>()).cast<float>());
    CHECK(mf.threshold() == Approx(md.threshold()).epsilon(1e-6));
    CHECK(mf.labels() == md.labels());
  }
}

TEST_CASE("pyod: bad input throws InvalidArgument naming the problem", "[pyod]") {
  const Eigen::MatrixXd X = standard_normal(50, 2, 3);
  using Catch::Matchers::Contains;
  using hbos::InvalidArgument;
  using hbos::PyodHbosd;

  SECTION("PyOD's parameter checks") {
    auto with = [](auto change) {
      hbos::PyodParams p;
      change(p);
      return p;
    };
    for (const double alpha : {0.0, 1.0, -0.1, 1.5, std::nan("")}) {
      CHECK_THROWS_WITH(PyodHbosd::fit(X, with([&](auto& p) { p.alpha = alpha; })),
                        Contains("alpha must lie in the open interval (0, 1)"));
    }
    for (const double tol : {0.0, 1.0, -1.0}) {
      CHECK_THROWS_WITH(PyodHbosd::fit(X, with([&](auto& p) { p.tol = tol; })),
                        Contains("tol must lie in the open interval (0, 1), got"));
    }
    for (const double c : {0.0, 0.51, -0.1}) {
      CHECK_THROWS_WITH(PyodHbosd::fit(X, with([&](auto& p) { p.contamination = c; })),
                        Contains("contamination must lie in (0, 0.5]"));
    }
    CHECK_NOTHROW(PyodHbosd::fit(X, with([](auto& p) { p.contamination = 0.5; })));
    for (const Index bins : {Index{2}, Index{1}, Index{0}, Index{-4}}) {
      CHECK_THROWS_WITH(PyodHbosd::fit(X, with([&](auto& p) { p.n_bins = bins; })),
                        Contains("n_bins must be > 2") && Contains(std::to_string(bins)));
    }
    CHECK_NOTHROW(PyodHbosd::fit(X, with([](auto& p) { p.n_bins = 3; })));
    // With auto_bins the integer is not used, so it is not checked (PyOD's n_bins is one or the
    // other).
    CHECK_NOTHROW(PyodHbosd::fit(X, with([](auto& p) {
                                   p.auto_bins = true;
                                   p.n_bins = 0;
                                 })));
  }

  SECTION("auto bins need more than 3 samples") {
    hbos::PyodParams p;
    p.auto_bins = true;
    CHECK_THROWS_WITH(PyodHbosd::fit(X.topRows(3), p),
                      Contains("more than 3 samples") && Contains("got 3"));
    const auto model = PyodHbosd::fit(X.topRows(4), p);
    CHECK(model.bins(0) == 1);  // sqrt(4) = 2: only b = 1 is searched
  }

  SECTION("empty input") {
    CHECK_THROWS_WITH(PyodHbosd::fit(Eigen::MatrixXd(0, 2)), Contains("empty matrix (0 x 2)"));
    CHECK_THROWS_WITH(PyodHbosd::fit(Eigen::MatrixXd(5, 0)), Contains("empty matrix (5 x 0)"));
    const auto model = PyodHbosd::fit(X);
    CHECK_THROWS_WITH(model.decision_function(Eigen::MatrixXd(0, 2)),
                      Contains("cannot score an empty matrix"));
    CHECK_THROWS_AS(PyodHbosd::fit(static_cast<const double*>(nullptr), 3, 2), InvalidArgument);
  }

  SECTION("NaN and infinity, at fit and at scoring") {
    Eigen::MatrixXd bad = X;
    bad(7, 1) = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH(PyodHbosd::fit(bad), Contains("X(7, 1) is not finite: nan"));
    bad(7, 1) = -std::numeric_limits<double>::infinity();
    CHECK_THROWS_WITH(PyodHbosd::fit(bad), Contains("X(7, 1) is not finite: -inf"));
    hbos::PyodParams auto_bins;
    auto_bins.auto_bins = true;
    bad(7, 1) = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH(PyodHbosd::fit(bad, auto_bins), Contains("X(7, 1) is not finite: nan"));
    const auto model = PyodHbosd::fit(X);
    CHECK_THROWS_WITH(model.decision_function(bad), Contains("X(7, 1) is not finite"));
    // Wherever it sits (vectorised min/max may then skip the true extremes), in every mode.
    Index missed = 0;
    for (Index i = 0; i < X.rows(); ++i) {
      for (const double v :
           {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        Eigen::MatrixXd one_bad = X;
        one_bad(i, 0) = v;
        for (const bool a : {false, true}) {
          auto_bins.auto_bins = a;
          try {
            (void)PyodHbosd::fit(one_bad, auto_bins);
            ++missed;
          } catch (const InvalidArgument& e) {
            missed += std::string(e.what()).find("is not finite") == std::string::npos ? 1 : 0;
          }
        }
        try {
          (void)model.decision_function(one_bad);
          ++missed;
        } catch (const InvalidArgument&) {
        }
      }
    }
    CHECK(missed == 0);
    CHECK_THROWS_AS(model.predict(bad), InvalidArgument);
  }

  SECTION("column count differing at scoring") {
    const auto model = PyodHbosd::fit(X);
    CHECK_THROWS_WITH(model.decision_function(Eigen::MatrixXd::Zero(4, 3)),
                      Contains("X has 3 columns but the model was fitted on 2 features"));
    const std::vector<double> buffer(6, 0.0);
    CHECK_THROWS_AS(model.decision_function(buffer.data(), 6, 1), InvalidArgument);
    CHECK_THROWS_WITH(model.bins(2), Contains("feature index must lie in [0, 2), got 2"));
    CHECK_THROWS_AS(model.lookup(-1, 0.0), InvalidArgument);
  }

  SECTION("bins narrower than the floating-point resolution (PyOD would score NaN)") {
    Eigen::MatrixXd tiny(4, 1);
    tiny << 1e16, 1e16, 1e16 + 2.0, 1e16 + 2.0;  // 10 bins of width 0.2 collapse onto 2 doubles
    CHECK_THROWS_WITH(PyodHbosd::fit(tiny),
                      Contains("narrower than the floating-point resolution"));
    const Eigen::MatrixXd huge = (Eigen::MatrixXd(2, 1) << -1e308, 1e308).finished();
    CHECK_THROWS_WITH(PyodHbosd::fit(huge), Contains("overflows a double"));
    // A range of one denormal: numpy's step is 0, every edge rounds to 0.
    Eigen::MatrixXd denormal(16, 1);
    for (Index i = 0; i < 16; ++i) denormal(i, 0) = i % 3 == 0 ? 5e-324 : 0.0;
    CHECK_THROWS_WITH(PyodHbosd::fit(denormal), Contains("edges 0 and 1 are equal"));
    hbos::PyodParams auto_bins;
    auto_bins.auto_bins = true;
    CHECK_THROWS_AS(PyodHbosd::fit(denormal, auto_bins), InvalidArgument);
    // Subnormal values spread over a range of distinct edges: the edges exist, but a count over
    // a subnormal width overflows the density, and PyOD scores -inf; refused (issue 11).
    Eigen::MatrixXd subnormal(16, 1);
    for (Index i = 0; i < 16; ++i) subnormal(i, 0) = static_cast<double>(i) * 1e-310;
    for (const bool a : {false, true}) {
      auto_bins.auto_bins = a;
      CHECK_THROWS_WITH(PyodHbosd::fit(subnormal, auto_bins), Contains("overflows a double"));
    }
    // Small but normal values are fine.
    const Eigen::MatrixXd small = subnormal * 1e10;
    for (const bool a : {false, true}) {
      hbos::PyodParams fresh;
      fresh.auto_bins = a;
      const auto model = PyodHbosd::fit(small, fresh);
      CHECK(model.counts(0).sum() == 16);
      CHECK(model.decision_scores().allFinite());
      CHECK(model.decision_function(small) == model.decision_scores());
    }
  }
}

TEST_CASE("pyod: a constant feature and a single sample follow numpy", "[pyod]") {
  Eigen::MatrixXd X(6, 2);
  X << 3.0, 0.0, 3.0, 1.0, 3.0, 2.0, 3.0, 3.0, 3.0, 4.0, 3.0, 5.0;
  const auto model = hbos::PyodHbosd::fit(X);
  // numpy widens a constant range by 0.5 each side: edges 2.5, 2.6, ..., 3.5.
  CHECK(model.bin_edges(0)[0] == 2.5);
  CHECK(model.bin_edges(0)[10] == 3.5);
  CHECK(model.counts(0)[5] == 6);  // 3.0 = 0.5 * 1 + 2.5 lands in [e_5, e_6)
  const auto single = hbos::PyodHbosd::fit(Eigen::MatrixXd::Constant(1, 1, 4.0));
  CHECK(single.n_samples() == 1);
  CHECK(single.threshold() == single.decision_scores()[0]);
  CHECK(single.labels()[0] == 0);
}

TEST_CASE("pyod defect 1: a value on an interior edge is scored with the bin below",
          "[pyod][defect]") {
  // An integer feature: value v occurs count[v] times. With 5 bins over [0, 5] the edges are the
  // integers, so 1, 2, 3 and 4 sit on interior edges: counted in bin v, scored with bin v - 1.
  const std::vector<Index> count = {40, 1, 60, 50, 30, 19};  // value 1 is rare
  std::vector<double> values;
  for (std::size_t v = 0; v < count.size(); ++v) {
    values.insert(values.end(), static_cast<std::size_t>(count[v]), static_cast<double>(v));
  }
  const Eigen::Map<const Eigen::MatrixXd> X(values.data(), static_cast<Index>(values.size()), 1);
  hbos::PyodParams params;
  params.n_bins = 5;
  const auto model = hbos::PyodHbosd::fit(X, params);
  REQUIRE(model.bin_edges(0) == (Eigen::VectorXd(6) << 0, 1, 2, 3, 4, 5).finished());
  CHECK(model.counts(0) == (hbos::PyodHbosd::Counts(5) << 40, 1, 60, 50, 49).finished());

  auto score_of = [&](double v) {
    return model.decision_function(Eigen::MatrixXd::Constant(1, 1, v))[0];
  };
  const hbos::PyodLookup rare = model.lookup(0, 1.0);
  CHECK(rare.on_interior_edge);
  CHECK(rare.bin == 0);  // the rare value borrows the density of the 40 zeros
  const hbos::PyodLookup common = model.lookup(0, 2.0);
  CHECK(common.on_interior_edge);
  CHECK(common.bin == 1);  // the most common value gets the density of the single 1
  // Hence the rare value looks normal and the most common one is the most anomalous in the data.
  CHECK(score_of(1.0) == Approx(1.7369655941662059).epsilon(1e-12));  // -log2(40/200 + 0.1)
  CHECK(score_of(2.0) == Approx(3.251538766995964).epsilon(1e-12));   // -log2(1/200 + 0.1)
  CHECK(score_of(1.0) < score_of(2.0));
  CHECK(model.decision_scores().maxCoeff() == score_of(2.0));
  // The 60 twos (30 % of the data) share that top score, so the 90th percentile is that score
  // and no sample is labelled an outlier.
  CHECK(model.threshold() == score_of(2.0));
  CHECK(model.labels().sum() == 0);
  // The count bin of the same value would have given the opposite ranking.
  CHECK(-std::log2(model.densities(0)[1] + 0.1) > -std::log2(model.densities(0)[2] + 0.1));

  // On real data: cardio puts 1069 training values exactly on interior edges at B = 10
  // (meta.json), each scored with its neighbour bin. Whether a value hits an edge exactly is a
  // matter of the last bits: rescaling by 1 + 1e-12 leaves 206 on edges, and ROC-AUC moves by
  // 0.014, far more than any real change of 1e-12 could justify.
  const Eigen::MatrixXd cardio = read_csv_matrix(kDataDir + "cardio/X.csv");
  const Eigen::VectorXd y = read_vector(kDataDir + "cardio/y.csv");
  const auto as_published = hbos::PyodHbosd::fit(cardio);
  CHECK(branch_counts(as_published, cardio)[1].second == 1069);
  CHECK(roc_auc(as_published.decision_scores(), y) == Approx(0.83772658610271911).epsilon(1e-12));
  const Eigen::MatrixXd nudged = cardio * (1.0 + 1e-12);
  const auto nudged_model = hbos::PyodHbosd::fit(nudged);
  CHECK(branch_counts(nudged_model, nudged)[1].second == 206);
  CHECK(roc_auc(nudged_model.decision_scores(), y) == Approx(0.85164446580609721).epsilon(1e-12));
}

TEST_CASE("pyod defect 2: alpha makes the scores depend on each feature's units",
          "[pyod][defect]") {
  // Multiplying a feature by 1000 divides its densities by 1000, so log2(h + alpha) ~ log2(alpha)
  // and the feature all but drops out of the score; dividing by 1000 lets the log-density
  // dominate alpha. Same data in other units, another ranking: a scale-free detector would give
  // the same ROC-AUC every time.
  const std::string dir = kDataDir + "cardio/";
  const Eigen::MatrixXd X = read_csv_matrix(dir + "X.csv");
  const Eigen::VectorXd y = read_vector(dir + "y.csv");
  auto auc_of = [&](const Eigen::MatrixXd& data) {
    return roc_auc(hbos::PyodHbosd::fit(data).decision_scores(), y);
  };
  CHECK(auc_of(X) == Approx(0.83772658610271911).epsilon(1e-12));  // auc.csv, PyOD defaults
  CHECK(auc_of(X * 1000.0) == Approx(0.81279868168085689).epsilon(1e-12));
  CHECK(auc_of(X / 1000.0) == Approx(0.87717316671244161).epsilon(1e-12));
  Eigen::MatrixXd one_feature = X;
  one_feature.col(9) *= 1000.0;
  CHECK(auc_of(one_feature) == Approx(0.76480705850041197).epsilon(1e-12));
  // Between the two unit choices 242 of the 1830 pairs of neighbouring rows swap order.
  const auto a = hbos::PyodHbosd::fit(X * 1000.0).decision_scores();
  const auto b = hbos::PyodHbosd::fit(X / 1000.0).decision_scores();
  Index discordant = 0;
  for (Index i = 0; i + 1 < a.size(); ++i) {
    discordant += ((a[i] - a[i + 1]) * (b[i] - b[i + 1]) < 0.0) ? 1 : 0;
  }
  CHECK(discordant == 242);
}

TEST_CASE("the default mode does not depend on the units (docs/pyod_compat.md, cardio table)",
          "[pyod][defect][docs]") {
  // The "default mode" and "10 plain bins, our convention" columns of the cardio table in
  // docs/pyod_compat.md, recomputed here (the PyOD-mode column is checked above). The model is
  // scale-free; what moves the 4th decimal is only the rounding of values that sit exactly on
  // bin edges under a decimal rescaling.
  const std::string dir = kDataDir + "cardio/";
  const Eigen::MatrixXd X = read_csv_matrix(dir + "X.csv");
  const Eigen::VectorXd y = read_vector(dir + "y.csv");
  hbos::HbosParams plain10;
  plain10.feature.binning.bins = 10;
  plain10.feature.binning.shifts = 1;
  auto auc_of = [&](const Eigen::MatrixXd& data, const hbos::HbosParams& params) {
    return roc_auc(hbos::Hbosd::fit(data, params).score(data), y);
  };
  Eigen::MatrixXd one_feature = X;
  one_feature.col(9) *= 1000.0;
  const std::vector<std::pair<std::string, Eigen::MatrixXd>> variants = {
      {"as distributed", X},
      {"x 1000", X * 1000.0},
      {"/ 1000", X / 1000.0},
      {"feature 9 x 1000", one_feature},
      {"x (1 + 1e-12)", X * (1.0 + 1e-12)}};
  const double default_auc[] = {0.9205, 0.9208, 0.9208, 0.9205, 0.9208};
  const double plain_auc[] = {0.8730, 0.8730, 0.8733, 0.8730, 0.8740};
  for (std::size_t v = 0; v < variants.size(); ++v) {
    INFO(variants[v].first);
    CHECK(auc_of(variants[v].second, hbos::HbosParams{}) == Approx(default_auc[v]).margin(5e-5));
    CHECK(auc_of(variants[v].second, plain10) == Approx(plain_auc[v]).margin(5e-5));
  }
  // Powers of two are exact: bit-identical scores.
  CHECK(hbos::Hbosd::fit(X * 1024.0).score(X * 1024.0) == hbos::Hbosd::fit(X).score(X));
}

TEST_CASE("pyod: the migration snippet of docs/pyod_compat.md", "[pyod][docs]") {
  const Eigen::MatrixXd X_train = read_csv_matrix(kDataDir + "pima/X.csv");
  const Eigen::MatrixXd X_test = read_csv_matrix(kDataDir + "pima/X_test.csv");
  // [pyod-migration]
  // Python: clf = HBOS(n_bins=20, alpha=0.01, tol=0.2, contamination=0.1).fit(X_train)
  hbos::PyodParams params;  // defaults are PyOD's: n_bins 10, alpha 0.1, tol 0.5, contamination 0.1
  params.n_bins = 20;       // n_bins="auto" is params.auto_bins = true
  params.alpha = 0.01;
  params.tol = 0.2;
  params.contamination = 0.1;
  const auto clf = hbos::PyodHbosd::fit(X_train, params);
  // clf.decision_scores_, clf.threshold_, clf.labels_:
  const Eigen::VectorXd& train_scores = clf.decision_scores();
  const double threshold = clf.threshold();
  const Eigen::VectorXi& train_labels = clf.labels();
  // clf.decision_function(X_test), clf.predict(X_test):
  const Eigen::VectorXd test_scores = clf.decision_function(X_test);
  const Eigen::VectorXi test_labels = clf.predict(X_test);
  // clf.bin_edges_[:, 0], clf.hist_[:, 0]:
  const Eigen::VectorXd& edges_0 = clf.bin_edges(0);
  const Eigen::VectorXd& hist_0 = clf.densities(0);
  // [pyod-migration]
  const std::string dir = kDataDir + "pima/";
  CHECK(train_scores == read_vector(dir + "scores_nb20_a0.01_tol0.2.csv"));
  CHECK(threshold == read_vector(dir + "threshold_nb20_a0.01_tol0.2.txt")[0]);
  CHECK(train_labels == read_vector(dir + "labels_nb20_a0.01_tol0.2.csv").cast<int>());
  CHECK(test_scores == read_vector(dir + "test_scores_nb20_a0.01_tol0.2.csv"));
  CHECK(test_labels == (test_scores.array() > threshold).cast<int>().matrix());
  CHECK(edges_0.size() == 21);
  CHECK(hist_0.size() == 20);
}
