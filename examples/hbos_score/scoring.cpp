#include "scoring.hpp"

#include <fmt/format.h>

#include <hbos/model.hpp>
#include <hbos/pyod.hpp>
#include <hbos/threshold.hpp>

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

void describe_default(ScoredTable& out, const HbosParams& params, const CsvTable& table) {
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
    periodic += table.feature_name(static_cast<Eigen::Index>(j));
  }
  out.model += periodic;
}

void run_default(ScoredTable& out, const ScoreOptions& options, const CsvTable& table) {
  const HbosParams params = make_params(options, table);
  const auto model = Hbosd::fit(table.features, params);
  out.contributions = model.contributions(table.features);
  out.scores = model.score(table.features);
  for (Eigen::Index j = 0; j < model.n_features(); ++j) {
    const Histogram<double>& h = model.histogram(j);
    const FeatureSpec& spec = params.spec(j);
    // Shifted histograms count on a grid `shifts` times finer; report the coarse bins the user
    // asked for (a constant feature has a single bin either way).
    const bool fine = spec.binning.method != BinningMethod::EqualFrequency && h.bins() > 1;
    out.bins.push_back(fine ? h.bins() / spec.binning.shifts : h.bins());
  }
  describe_default(out, params, table);
  const auto verdict = threshold_scores(out.scores, options.threshold);
  out.threshold = verdict.threshold;
  out.outlier = (!verdict.inlier).cast<int>();
  out.n_outliers = verdict.n_outliers();
}

void run_pyod(ScoredTable& out, const ScoreOptions& options, const CsvTable& table) {
  const PyodParams params = make_pyod_params(options);
  const auto model = PyodHbos<double>::fit(table.features, params);
  out.scores = model.decision_scores();
  const Eigen::Index n = table.rows();
  const Eigen::Index d = model.n_features();
  out.contributions.resize(n, d);
  for (Eigen::Index j = 0; j < d; ++j) {
    for (Eigen::Index i = 0; i < n; ++i) {
      out.contributions(i, j) = -model.lookup(j, table.features(i, j)).log_term;
    }
    out.bins.push_back(model.bins(j));
  }
  out.model = fmt::format("pyod: PyOD 3.6.5 HBOS, n_bins {}, alpha {}, tol {}",
                          params.auto_bins ? std::string("auto") : std::to_string(params.n_bins),
                          params.alpha, params.tol);
  if (std::holds_alternative<Contamination>(options.threshold)) {
    // PyOD's own threshold_ and labels_, bit for bit.
    out.threshold = model.threshold();
    out.outlier = model.labels();
  } else {
    const auto verdict = threshold_scores(out.scores, options.threshold);
    out.threshold = verdict.threshold;
    out.outlier = (!verdict.inlier).cast<int>();
  }
  out.n_outliers = out.outlier.sum();
}

}  // namespace

ScoredTable score_table(const ScoreOptions& options, const CsvTable& table) {
  ScoredTable out;
  if (options.mode == Mode::Pyod) {
    run_pyod(out, options, table);
  } else {
    run_default(out, options, table);
  }
  return out;
}

}  // namespace hbos::cli
