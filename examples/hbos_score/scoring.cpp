#include "scoring.hpp"

#include <fmt/format.h>

#include <hbos/model.hpp>
#include <hbos/pyod.hpp>
#include <hbos/pyod/detail/numpy_replica.hpp>
#include <hbos/threshold.hpp>

#include <utility>
#include <vector>

namespace hbos::cli {
namespace {

std::string describe(const FeatureSpec& spec) {
  const Binning& b = spec.binning;
  std::string bins;
  if (b.method == BinningMethod::FixedWidth) {
    bins = fmt::format("width {} from origin {}", b.width, b.origin);
  } else {
    bins = to_string(BinsChoice{b.rule, b.bins}) + " bins";
  }
  if (b.method != BinningMethod::EqualFrequency && b.shifts > 1) {
    bins += fmt::format(" x {} shifts (averaged shifted histograms)", b.shifts);
  }
  return to_string(b.method) + ", " + bins;
}

void describe_default(ScoredTable& out, const HbosParams& params, const CsvLayout& layout) {
  out.model = "default: " + describe(params.feature) + ", tail " + to_string(params.feature.tail);
  std::string periodic;
  for (std::size_t j = 0; j < params.features.size(); ++j) {
    if (!params.features[j].periodic) continue;
    if (periodic.empty()) {
      periodic = fmt::format("; periodic (period {:g} from {:g}): ", params.features[j].period,
                             params.features[j].period_start);
    } else {
      periodic += ", ";
    }
    periodic += layout.feature_name(static_cast<Eigen::Index>(j));
  }
  out.model += periodic;
}

/// Runs `fit_column(j)` for every feature; a library error names the feature by index and name
/// (the one-feature model it came from calls every feature "feature 0").
template <class FitColumn>
void for_each_feature(const CsvLayout& layout, Eigen::Index d, const FitColumn& fit_column) {
  for (Eigen::Index j = 0; j < d; ++j) {
    try {
      fit_column(j);
    } catch (const InvalidArgument& e) {
      // The re-thrown InvalidArgument adds the library's "hbos: " again: strip it here once.
      std::string message = e.what();
      for (const std::string own : {"hbos: ", "feature 0"})
        if (message.rfind(own, 0) == 0) message = message.substr(own.size());
      throw InvalidArgument(fmt::format("feature {} (\"{}\"){}{}", j, layout.feature_name(j),
                                        message.empty() || message[0] == ':' ? "" : ": ", message));
    }
  }
}

void run_default(ScoredTable& out, const ScoreOptions& options, const CsvLayout& layout) {
  const HbosParams params = make_params(options, layout);
  RowStore& values = out.contributions;
  const Eigen::Index n = values.rows();
  const Eigen::Index d = values.cols();
  auto matrix = values.matrix();
  Eigen::VectorXd column_scores(n);
  for_each_feature(layout, d, [&](Eigen::Index j) {
    HbosParams one = params;
    one.features.clear();
    if (!params.features.empty()) one.features.push_back(params.spec(j));
    one.feature = params.spec(j);
    const auto model = Hbosd::fit_and_score(matrix.col(j), column_scores, one);
    // A one-feature score is that feature's contribution, bit for bit.
    matrix.col(j) = column_scores;
    const Histogram<double>& h = model.histogram(0);
    const FeatureSpec& spec = one.feature;
    // Shifted histograms count on a grid `shifts` times finer; report the coarse bins the user
    // asked for (a constant feature has a single bin either way).
    const bool fine = spec.binning.method != BinningMethod::EqualFrequency && h.bins() > 1;
    out.bins.push_back(fine ? h.bins() / spec.binning.shifts : h.bins());
  });
  // The library adds the contributions in feature order, starting from the first.
  out.scores.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double* row = values.data() + i * d;
    double sum = row[0];
    for (Eigen::Index j = 1; j < d; ++j) sum += row[j];
    out.scores[i] = sum;
  }
  describe_default(out, params, layout);
  const auto verdict = threshold_scores(out.scores, options.threshold);
  out.threshold = verdict.threshold;
  out.outlier = (!verdict.inlier).cast<int>();
  out.n_outliers = verdict.n_outliers();
}

void run_pyod(ScoredTable& out, const ScoreOptions& options, const CsvLayout& layout) {
  const PyodParams params = make_pyod_params(options);
  RowStore& values = out.contributions;
  const Eigen::Index n = values.rows();
  const Eigen::Index d = values.cols();
  // Each feature on its own, as a one-feature PyodHbos would fit it (errors say "feature 0",
  // renamed by for_each_feature), without the look-up grid such a model keeps for scoring new
  // data: with few rows building it would cost more than the fit.
  std::vector<double> terms(static_cast<std::size_t>(n));
  for_each_feature(layout, d, [&](Eigen::Index j) {
    double* column = values.data() + j;
    const auto feature = PyodFeatureModel<double>::fit(column, d, n, 0, params, terms.data());
    // A one-feature decision score is -log2(density + alpha) of its bin: the contribution.
    for (Eigen::Index i = 0; i < n; ++i) column[i * d] = -terms[static_cast<std::size_t>(i)];
    out.bins.push_back(feature.bins());
  });
  // PyOD sums the log terms with numpy's pairwise summation (a plain loop below 8 features);
  // the contributions are their negations, and negation commutes with rounding.
  out.scores.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    out.scores[i] = detail::numpy_pairwise_sum(values.data() + i * d, d, 1);
  }
  out.model = fmt::format("pyod: PyOD 3.6.5 HBOS, n_bins {}, alpha {}, tol {}",
                          params.auto_bins ? std::string("auto") : std::to_string(params.n_bins),
                          params.alpha, params.tol);
  if (std::holds_alternative<Contamination>(options.threshold)) {
    // PyOD's own threshold_ and labels_, bit for bit.
    std::vector<double> scratch;
    out.threshold = detail::pyod_threshold(out.scores.data(), n, params.contamination, scratch);
    out.outlier = (out.scores.array() > out.threshold).cast<int>();
  } else {
    const auto verdict = threshold_scores(out.scores, options.threshold);
    out.threshold = verdict.threshold;
    out.outlier = (!verdict.inlier).cast<int>();
  }
  out.n_outliers = out.outlier.sum();
}

}  // namespace

ScoredTable score_table(const ScoreOptions& options, const CsvLayout& layout, RowStore values) {
  ScoredTable out;
  out.contributions = std::move(values);
  if (options.mode == Mode::Pyod) {
    run_pyod(out, options, layout);
  } else {
    run_default(out, options, layout);
  }
  return out;
}

}  // namespace hbos::cli
