// Tests of examples/hbos_score/roc_auc.hpp against hand-computed values, a brute-force pair count
// and scikit-learn's own number for PyOD's scores on ODDS vertebral.

#include "roc_auc.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

using hbos::cli::roc_auc;

namespace {

Eigen::VectorXd scores_of(std::initializer_list<double> values) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (const double x : values) v[i++] = x;
  return v;
}

Eigen::VectorXi labels_of(std::initializer_list<int> values) {
  Eigen::VectorXi v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (const int x : values) v[i++] = x;
  return v;
}

/// The definition: the share of (outlier, inlier) pairs ranked correctly, ties counting 1/2.
double brute_force_auc(const Eigen::VectorXd& s, const Eigen::VectorXi& y) {
  double wins = 0.0;
  double pairs = 0.0;
  for (Eigen::Index i = 0; i < s.size(); ++i) {
    if (y[i] != 1) continue;
    for (Eigen::Index j = 0; j < s.size(); ++j) {
      if (y[j] != 0) continue;
      pairs += 1.0;
      wins += s[i] > s[j] ? 1.0 : s[i] == s[j] ? 0.5 : 0.0;
    }
  }
  return wins / pairs;
}

Eigen::VectorXd read_column(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in.good());
  std::vector<double> values;
  double v = 0.0;
  while (in >> v) values.push_back(v);
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

}  // namespace

TEST_CASE("ROC-AUC of hand-computed cases", "[roc_auc]") {
  CHECK(*roc_auc(scores_of({0.1, 0.4, 0.35, 0.8}), labels_of({0, 0, 1, 1})) == 0.75);
  CHECK(*roc_auc(scores_of({1, 2, 3, 4}), labels_of({0, 0, 1, 1})) == 1.0);
  CHECK(*roc_auc(scores_of({4, 3, 2, 1}), labels_of({0, 0, 1, 1})) == 0.0);
  CHECK(*roc_auc(scores_of({7, 7, 7, 7, 7}), labels_of({0, 1, 0, 1, 0})) == 0.5);
  // Pairs (outlier, inlier): (2,1) 1, (2,2) 1/2, (3,1) 1, (3,2) 1 -> 3.5 / 4.
  CHECK(*roc_auc(scores_of({1, 2, 2, 3}), labels_of({0, 1, 0, 1})) == 0.875);
  CHECK(*roc_auc(scores_of({-0.0, 0.0}), labels_of({1, 0})) == 0.5);  // -0 == 0 is a tie
}

TEST_CASE("ROC-AUC equals the pair count exactly, in any order", "[roc_auc][property]") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 30; ++trial) {
    const Eigen::Index n = 2 + trial * 13;
    Eigen::VectorXd s(n);
    Eigen::VectorXi y(n);
    std::uniform_int_distribution<int> value(0, 4 + trial);  // many ties
    for (Eigen::Index i = 0; i < n; ++i) {
      s[i] = static_cast<double>(value(rng)) * 0.37;
      y[i] = static_cast<int>(rng() % 3 == 0);
    }
    y[0] = 1;
    y[1] = 0;
    INFO("trial " << trial);
    const auto auc = roc_auc(s, y);
    REQUIRE(auc.has_value());
    CHECK(*auc == brute_force_auc(s, y));

    std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
    for (Eigen::Index i = 0; i < n; ++i) order[static_cast<std::size_t>(i)] = i;
    std::shuffle(order.begin(), order.end(), rng);
    Eigen::VectorXd s2(n);
    Eigen::VectorXi y2(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      s2[i] = s[order[static_cast<std::size_t>(i)]];
      y2[i] = y[order[static_cast<std::size_t>(i)]];
    }
    CHECK(*roc_auc(s2, y2) == *auc);
  }
}

TEST_CASE("ROC-AUC matches scikit-learn on PyOD's vertebral scores", "[roc_auc]") {
  const std::string dir = HBOS_CLI_TEST_DATA "/pyod_vertebral/";
  const Eigen::VectorXd scores = read_column(dir + "scores.csv");
  const Eigen::VectorXi labels = read_column(dir + "y.csv").cast<int>();
  REQUIRE(scores.size() == 240);
  // auc.csv, vertebral, roc_auc_default (sklearn.metrics.roc_auc_score).
  CHECK(*roc_auc(scores, labels) == Approx(0.35063492063492063).margin(1e-15));
}

TEST_CASE("ROC-AUC is undefined for one class and rejects bad input", "[roc_auc][errors]") {
  CHECK_FALSE(roc_auc(scores_of({1, 2}), labels_of({0, 0})).has_value());
  CHECK_FALSE(roc_auc(scores_of({1, 2}), labels_of({1, 1})).has_value());
  REQUIRE_THROWS_WITH(roc_auc(scores_of({1, 2}), labels_of({0})),
                      Catch::Contains("2 scores but 1 labels"));
  REQUIRE_THROWS_WITH(roc_auc(scores_of({1, 2}), labels_of({0, 2})),
                      Catch::Contains("label 1 is 2"));
  REQUIRE_THROWS_WITH(
      roc_auc(scores_of({1, std::numeric_limits<double>::quiet_NaN()}), labels_of({0, 1})),
      Catch::Contains("score 1 is NaN"));
}
