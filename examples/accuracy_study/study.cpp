#include "study.hpp"

#include <hbos/model.hpp>
#include <hbos/pyod.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "roc_auc.hpp"

namespace hbos::study {
namespace {

HbosParams equal_width(BinCountRule rule, Eigen::Index bins, Eigen::Index shifts) {
  HbosParams params;
  params.feature.binning.method = BinningMethod::EqualWidth;
  params.feature.binning.rule = rule;
  params.feature.binning.bins = bins;
  params.feature.binning.shifts = shifts;
  return params;
}

Method hbos_method(std::string key, std::string title, std::string description,
                   const HbosParams& params, Transform transform = Transform::None,
                   bool main = false) {
  Method m;
  m.key = std::move(key);
  m.title = std::move(title);
  m.description = std::move(description);
  m.transform = transform;
  m.main = main;
  m.score = [params](const Eigen::MatrixXd& x) -> Eigen::VectorXd {
    return Hbosd::fit(x, params).score(x);
  };
  return m;
}

Method pyod_method(std::string key, std::string title, std::string description, Transform transform,
                   bool main) {
  Method m;
  m.key = std::move(key);
  m.title = std::move(title);
  m.description = std::move(description);
  m.transform = transform;
  m.main = main;
  m.score = [](const Eigen::MatrixXd& x) -> Eigen::VectorXd {
    return PyodHbos<double>::fit(x, PyodParams{}).decision_scores();
  };
  return m;
}

/// An integer uniform in [lo, hi] from mt19937_64, whose output sequence the standard fixes
/// (std::uniform_int_distribution is not portable; its modulo bias here is below 2^-50).
long long uniform_int(std::mt19937_64& rng, long long lo, long long hi) {
  return lo + static_cast<long long>(rng() % static_cast<std::uint64_t>(hi - lo + 1));
}

/// The smallest power of two >= max |x_j| (1 for a zero column), computed exactly.
double magnitude(const Eigen::MatrixXd& x, Eigen::Index j) {
  const double m = x.col(j).cwiseAbs().maxCoeff();
  if (!(m > 0.0)) return 1.0;
  int exponent = 0;
  const double fraction =
      std::frexp(m, &exponent);  // m = fraction * 2^exponent, fraction in [0.5, 1)
  return std::ldexp(1.0, fraction == 0.5 ? exponent - 1 : exponent);
}

/// FNV-1a of a data set's name: its transforms do not depend on which other sets are run.
std::uint64_t name_hash(const std::string& name) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const char c : name) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return hash;
}

Eigen::MatrixXd transformed(const Eigen::MatrixXd& x, Transform transform, std::uint64_t seed) {
  switch (transform) {
    case Transform::PowerOfTwo:
      return rescale_power_of_two(x, seed);
    case Transform::Units:
      return change_units(x, seed);
    case Transform::None:
      break;
  }
  return x;
}

}  // namespace

std::vector<Method> study_methods() {
  std::vector<Method> methods;
  const char* default_text =
      "the default mode: 5 equal-width bins x 5 shifts (averaged shifted histograms)";
  const char* pyod_text = "the PyOD mode: PyOD 3.6.5's HBOS defaults (10 bins, alpha 0.1, tol 0.5)";
  methods.push_back(
      hbos_method("default", "default", default_text, HbosParams{}, Transform::None, true));
  methods.push_back(hbos_method("classic10", "classic-10",
                                "10 plain equal-width bins (Goldstein & Dengel's static bins)",
                                equal_width(BinCountRule::Fixed, 10, 1), Transform::None, true));
  methods.push_back(pyod_method("pyod", "PyOD", pyod_text, Transform::None, true));
  methods.push_back(
      pyod_method("pyod_rescaled", "PyOD rescaled",
                  "the PyOD mode, every feature multiplied by a power of two in [1e-3, 1e3]",
                  Transform::PowerOfTwo, true));
  methods.push_back(
      hbos_method("default_rescaled", "default rescaled",
                  "the default mode, every feature multiplied by a power of two in [1e-3, 1e3]",
                  HbosParams{}, Transform::PowerOfTwo, true));
  methods.push_back(
      hbos_method("default_units", "default, units changed",
                  "the default mode, every feature shifted and multiplied by a decimal "
                  "factor in [1e-3, 1e3]",
                  HbosParams{}, Transform::Units, true));
  methods.push_back(
      pyod_method("pyod_units", "PyOD, units changed",
                  "the PyOD mode, every feature shifted and multiplied by a decimal factor "
                  "in [1e-3, 1e3]",
                  Transform::Units, true));
  methods.push_back(hbos_method("classic10_ash5", "10 x 5 shifts", "10 equal-width bins x 5 shifts",
                                equal_width(BinCountRule::Fixed, 10, 5)));
  HbosParams frequency = equal_width(BinCountRule::Fixed, 10, 1);
  frequency.feature.binning.method = BinningMethod::EqualFrequency;
  methods.push_back(hbos_method("equal_frequency10", "equal-freq 10",
                                "10 equal-frequency bins (Goldstein & Dengel's dynamic bins)",
                                frequency));
  methods.push_back(hbos_method("sturges", "Sturges", "equal-width, Sturges' bin count, no shifts",
                                equal_width(BinCountRule::Sturges, 0, 1)));
  methods.push_back(hbos_method("sturges_ash5", "Sturges x 5",
                                "equal-width, Sturges' bin count x 5 shifts",
                                equal_width(BinCountRule::Sturges, 0, 5)));
  methods.push_back(hbos_method("birge", "Birgé–R.",
                                "equal-width, Birgé–Rozenblac's bin count, no shifts",
                                equal_width(BinCountRule::BirgeRozenblac, 0, 1)));
  methods.push_back(hbos_method("birge_ash5", "Birgé–R. x 5",
                                "equal-width, Birgé–Rozenblac's bin count x 5 shifts",
                                equal_width(BinCountRule::BirgeRozenblac, 0, 5)));
  return methods;
}

Eigen::MatrixXd rescale_power_of_two(const Eigen::MatrixXd& x, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Eigen::MatrixXd out(x.rows(), x.cols());
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    out.col(j) = x.col(j) * std::ldexp(1.0, static_cast<int>(uniform_int(rng, -9, 9)));
  }
  return out;
}

Eigen::MatrixXd change_units(const Eigen::MatrixXd& x, std::uint64_t seed) {
  static constexpr double kPowersOfTen[] = {1e-3, 1e-2, 1e-1, 1.0, 1e1, 1e2};
  std::mt19937_64 rng(seed);
  Eigen::MatrixXd out(x.rows(), x.cols());
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    const double digits = static_cast<double>(uniform_int(rng, 100, 999)) / 100.0;
    const double factor = digits * kPowersOfTen[uniform_int(rng, 0, 5)];
    const double shift = static_cast<double>(uniform_int(rng, -1000, 1000)) * magnitude(x, j);
    out.col(j) = (x.col(j).array() + shift) * factor;
  }
  return out;
}

StudyResult run_study(const std::vector<DataSet>& sets, const std::vector<Method>& methods,
                      std::uint64_t seed, std::FILE* log) {
  StudyResult result;
  result.methods = methods;
  const auto n_sets = static_cast<Eigen::Index>(sets.size());
  const auto n_methods = static_cast<Eigen::Index>(methods.size());
  result.auc.resize(n_sets, n_methods);
  result.seconds.resize(n_sets, n_methods);
  for (Eigen::Index s = 0; s < n_sets; ++s) {
    const DataSet& set = sets[static_cast<std::size_t>(s)];
    result.datasets.push_back(set.name);
    result.rows.push_back(set.x.rows());
    result.features.push_back(set.x.cols());
    result.outliers.push_back(set.y.sum());
    const std::uint64_t set_seed = seed + name_hash(set.name);
    const Eigen::MatrixXd rescaled = transformed(set.x, Transform::PowerOfTwo, set_seed);
    const Eigen::MatrixXd units = transformed(set.x, Transform::Units, set_seed);
    for (Eigen::Index m = 0; m < n_methods; ++m) {
      const Method& method = methods[static_cast<std::size_t>(m)];
      const auto start = std::chrono::steady_clock::now();
      const Eigen::MatrixXd& data = method.transform == Transform::PowerOfTwo ? rescaled
                                    : method.transform == Transform::Units    ? units
                                                                              : set.x;
      const Eigen::VectorXd scores = method.score(data);
      result.seconds(s, m) =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const auto auc = cli::roc_auc(scores, set.y);
      if (!auc) throw std::invalid_argument(set.name + ": the labels hold one class only");
      result.auc(s, m) = *auc;
    }
    if (log != nullptr) {
      std::fprintf(log, "%-12s %6lld x %-4lld", set.name.c_str(),
                   static_cast<long long>(set.x.rows()), static_cast<long long>(set.x.cols()));
      for (Eigen::Index m = 0; m < n_methods; ++m) std::fprintf(log, " %.4f", result.auc(s, m));
      std::fprintf(log, "  (%.3f s)\n", result.seconds.row(s).sum());
    }
  }
  return result;
}

}  // namespace hbos::study
