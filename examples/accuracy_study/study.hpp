#pragma once
/// \file
/// The accuracy study: ROC-AUC of several HBOS configurations on labelled data sets, fitted on
/// all rows without scaling, plus the scale test (every feature rescaled and shifted).

#include <Eigen/Core>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace hbos::study {

/// A labelled data set: rows = samples, labels 1 = outlier.
struct DataSet {
  std::string name;
  Eigen::MatrixXd x;
  Eigen::VectorXi y;
};

/// How a data set is changed before a method sees it (the scale test).
enum class Transform {
  None,        ///< the data as given
  PowerOfTwo,  ///< rescale_power_of_two: exact in floating point
  Units        ///< change_units: a realistic change of units and origin, rounded
};

/// One column of the result table: a scorer, run on the data as given or transformed.
struct Method {
  std::string key;          ///< column name in the CSV, e.g. `default`, `pyod_rescaled`
  std::string title;        ///< column title in the Markdown table
  std::string description;  ///< what it is, for the legend
  std::function<Eigen::VectorXd(const Eigen::MatrixXd&)> score;
  Transform transform = Transform::None;
  bool main = false;  ///< shown in the main table (the others go to the second table)
};

/// The configurations of the study, in table order: the default mode, classic 10 plain bins, the
/// PyOD mode, the scale test of both, then a few other binnings with and without shifts.
[[nodiscard]] std::vector<Method> study_methods();

/// Every column multiplied by its own factor 2^k, k uniform in {-9, ..., 9} (so the factor lies
/// in [1e-3, 1e3]), drawn from mt19937_64 seeded with `seed`. Multiplying by a power of two is
/// exact in floating point, so every value keeps its bin: a scale-invariant model must give
/// bit-identical scores, and any change is a real scale dependence (PyOD's alpha).
[[nodiscard]] Eigen::MatrixXd rescale_power_of_two(const Eigen::MatrixXd& x, std::uint64_t seed);

/// Every column shifted by m * s (m uniform in {-1000, ..., 1000}, s the smallest power of two
/// >= the column's largest magnitude), then multiplied by d * 10^k (d uniform in {1.00, 1.01,
/// ..., 9.99}, k uniform in {-3, ..., 2}, so the factor lies in [1e-3, 1e3]): a change of units
/// and origin. The results are rounded, so values that lie exactly on a bin edge (common for
/// discretised features) may change sides: mathematically invariant models may move slightly.
/// Only correctly rounded IEEE operations on integers and literals are used (no pow or exp), so
/// the data are the same on every platform.
[[nodiscard]] Eigen::MatrixXd change_units(const Eigen::MatrixXd& x, std::uint64_t seed);

/// ROC-AUC per data set (rows) and method (columns).
struct StudyResult {
  std::vector<std::string> datasets;
  std::vector<Method> methods;
  Eigen::MatrixXd auc;                                 ///< datasets x methods
  Eigen::MatrixXd seconds;                             ///< datasets x methods: fit + score time
  std::vector<Eigen::Index> rows, features, outliers;  ///< per data set
};

/// Runs every method on every data set. The transforms of a data set are drawn with the seed
/// `seed` + FNV-1a(its name), so they do not depend on which other sets are run.
/// Progress goes to `log` (may be null).
[[nodiscard]] StudyResult run_study(const std::vector<DataSet>& sets,
                                    const std::vector<Method>& methods, std::uint64_t seed,
                                    std::FILE* log);

}  // namespace hbos::study
