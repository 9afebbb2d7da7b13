// The smallest useful hbos program: fit on a data set, score it, flag the outliers.
// Built by CI against the installed package to prove `find_package(hbos)` works.
#include <hbos/hbos.hpp>

#include <cstdio>
#include <random>

int main() {
  std::mt19937 rng(1);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd x(1000, 2);
  for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = normal(rng);
  x.row(0) << 8.0, -9.0;  // one obvious outlier

  const auto model = hbos::Hbosd::fit(x);                                         // 1. fit
  const Eigen::VectorXd scores = model.score(x);                                  // 2. score
  const auto result = hbos::threshold_scores(scores, hbos::Contamination{0.01});  // 3. threshold

  std::printf("hbos %d.%d.%d: %ld of %ld rows flagged; row 0 scores %.2f (threshold %.2f)\n",
              hbos::kVersionMajor, hbos::kVersionMinor, hbos::kVersionPatch,
              static_cast<long>(result.n_outliers()), static_cast<long>(x.rows()), scores(0),
              result.threshold);
  return result.inlier(0) ? 1 : 0;  // the planted outlier must be flagged
}
