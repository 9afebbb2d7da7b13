#include "score_options.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "column_selector.hpp"

namespace hbos::cli {
namespace {

/// A whole string as a finite double, or nullopt.
std::optional<double> to_double(std::string_view text) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

[[noreturn]] void threshold_error(std::string_view text, const std::string& why) {
  throw std::invalid_argument(fmt::format(
      "\"{}\": {} (expected adaptive[:RANGE_ALPHA], contamination[:SHARE], mad[:K] or fixed:VALUE)",
      text, why));
}

}  // namespace

BinsChoice parse_bins(std::string_view text) {
  if (text == "sqrt") return {BinCountRule::Sqrt, 0};
  if (text == "sturges") return {BinCountRule::Sturges, 0};
  if (text == "scott") return {BinCountRule::Scott, 0};
  if (text == "fd" || text == "freedman-diaconis") return {BinCountRule::FreedmanDiaconis, 0};
  if (text == "birge" || text == "birge-rozenblac" || text == "auto") {
    return {BinCountRule::BirgeRozenblac, 0};
  }
  long long count = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, count);
  constexpr long long kMaxBins = 65536;  // Binning::max_bins' default
  if (!text.empty() && ec == std::errc() && ptr == end && count >= 1 && count <= kMaxBins) {
    return {BinCountRule::Fixed, static_cast<Eigen::Index>(count)};
  }
  throw std::invalid_argument(fmt::format(
      "\"{}\" is neither a bin count in [1, {}] nor one of sqrt, sturges, scott, fd, birge, auto",
      text, kMaxBins));
}

ThresholdRule parse_threshold(std::string_view text) {
  const std::size_t colon = text.find(':');
  const std::string_view name = text.substr(0, colon);
  const bool has_value = colon != std::string_view::npos;
  std::optional<double> value;
  if (has_value) {
    value = to_double(text.substr(colon + 1));
    if (!value) threshold_error(text, "the parameter is not a finite number");
  }
  if (name == "adaptive") {
    const double a = value.value_or(0.7);
    if (!(a > 0.0 && a < 1.0)) threshold_error(text, "adaptive's range_alpha must lie in (0, 1)");
    return AdaptiveRange{a};
  }
  if (name == "contamination") {
    const double c = value.value_or(0.1);
    if (!(c > 0.0 && c <= 0.5)) threshold_error(text, "contamination must lie in (0, 0.5]");
    return Contamination{c};
  }
  if (name == "mad") {
    const double k = value.value_or(3.0);
    if (!(k > 0.0)) threshold_error(text, "mad's k must be > 0");
    return MedianMad{k, true};
  }
  if (name == "fixed") {
    if (!value) threshold_error(text, "fixed needs a value, e.g. fixed:12.5");
    return FixedThreshold{*value};
  }
  threshold_error(text, "unknown rule");
}

std::string to_string(const ThresholdRule& rule) {
  if (const auto* r = std::get_if<AdaptiveRange>(&rule))
    return fmt::format("adaptive:{}", r->range_alpha);
  if (const auto* r = std::get_if<Contamination>(&rule)) {
    return fmt::format("contamination:{}", r->contamination);
  }
  if (const auto* r = std::get_if<MedianMad>(&rule)) return fmt::format("mad:{}", r->k);
  return fmt::format("fixed:{}", std::get<FixedThreshold>(rule).value);
}

std::string to_string(const BinsChoice& bins) {
  switch (bins.rule) {
    case BinCountRule::Fixed:
      return std::to_string(bins.count);
    case BinCountRule::Sqrt:
      return "sqrt";
    case BinCountRule::Sturges:
      return "sturges";
    case BinCountRule::Scott:
      return "scott";
    case BinCountRule::FreedmanDiaconis:
      return "fd";
    case BinCountRule::BirgeRozenblac:
      return "birge";
  }
  return "?";
}

std::string to_string(BinningMethod method) {
  switch (method) {
    case BinningMethod::EqualWidth:
      return "equal-width";
    case BinningMethod::FixedWidth:
      return "fixed-width";
    case BinningMethod::EqualFrequency:
      return "equal-frequency";
  }
  return "?";
}

std::string to_string(Tail tail) {
  switch (tail) {
    case Tail::Both:
      return "both";
    case Tail::Upper:
      return "upper";
    case Tail::Lower:
      return "lower";
  }
  return "?";
}

void check_combinations(const ScoreOptions& o) {
  auto reject = [](const std::string& message) { throw std::invalid_argument(message); };
  if (o.mode == Mode::Pyod) {
    const char* why = " is not available with --mode pyod (PyOD's HBOS has plain equal-width bins)";
    if (o.binning) reject(std::string("--binning") + why);
    if (o.width) reject(std::string("--width") + why);
    if (o.origin) reject(std::string("--origin") + why);
    if (o.shifts) reject(std::string("--shifts") + why);
    if (o.tail) reject(std::string("--tail") + why);
    if (!o.periodic_columns.empty()) reject(std::string("--periodic-columns") + why);
    if (o.period || o.period_start) reject(std::string("--period/--period-start") + why);
    if (o.bins && o.bins->rule != BinCountRule::Fixed &&
        o.bins->rule != BinCountRule::BirgeRozenblac) {
      reject("--bins " + to_string(*o.bins) +
             " is not available with --mode pyod (PyOD takes a count > 2 or auto)");
    }
    if (o.bins && o.bins->rule == BinCountRule::Fixed && o.bins->count <= 2) {
      reject("--bins must be > 2 with --mode pyod (PyOD rejects n_bins <= 2), got " +
             to_string(*o.bins));
    }
    if (o.alpha && !(*o.alpha > 0.0 && *o.alpha < 1.0)) {
      reject(fmt::format("--alpha must lie in (0, 1), got {}", *o.alpha));
    }
    if (o.tol && !(*o.tol > 0.0 && *o.tol < 1.0)) {
      reject(fmt::format("--tol must lie in (0, 1), got {}", *o.tol));
    }
    return;
  }
  if (o.alpha)
    reject("--alpha belongs to --mode pyod (the default mode has no density regulariser)");
  if (o.tol) reject("--tol belongs to --mode pyod (the default mode's range tolerance is fixed)");
  const BinningMethod method = o.binning.value_or(BinningMethod::EqualWidth);
  if (method == BinningMethod::FixedWidth) {
    if (!o.width) reject("--binning fixed-width needs --width (the bin width, in feature units)");
    if (o.bins) reject("--bins does not apply to --binning fixed-width (the width sets the bins)");
  } else {
    if (o.width) reject("--width applies to --binning fixed-width only");
    if (o.origin) reject("--origin applies to --binning fixed-width only");
  }
  if (o.width && !(*o.width > 0.0)) reject(fmt::format("--width must be > 0, got {}", *o.width));
  if (method == BinningMethod::EqualFrequency) {
    if (o.shifts) reject("--shifts applies to equal-width and fixed-width binning only");
    if (!o.periodic_columns.empty()) {
      reject(
          "--periodic-columns needs equal-width or fixed-width binning (equal-frequency bins are "
          "not defined on a circle)");
    }
  }
  if (o.shifts && *o.shifts < 1) reject(fmt::format("--shifts must be >= 1, got {}", *o.shifts));
  if (o.periodic_columns.empty() && (o.period || o.period_start)) {
    reject("--period/--period-start need --periodic-columns");
  }
  if (o.period && !(*o.period > 0.0))
    reject(fmt::format("--period must be > 0, got {}", *o.period));
}

HbosParams make_params(const ScoreOptions& o, const CsvLayout& table) {
  HbosParams params;  // feature = default_feature(): 5 equal-width bins x 5 shifts
  Binning& b = params.feature.binning;
  if (o.binning) b.method = *o.binning;
  if (o.bins) {
    b.rule = o.bins->rule;
    if (o.bins->rule == BinCountRule::Fixed) b.bins = o.bins->count;
  }
  if (o.width) b.width = *o.width;
  if (o.origin) b.origin = *o.origin;
  if (o.shifts) b.shifts = *o.shifts;
  if (o.tail) params.feature.tail = *o.tail;
  if (o.periodic_columns.empty()) return params;

  // Periodic columns get their own spec: the same binning on a circle, no tail.
  FeatureSpec periodic = params.feature;
  periodic.periodic = true;
  periodic.tail = Tail::Both;
  if (o.period_start) periodic.period_start = *o.period_start;
  if (o.period) periodic.period = *o.period;
  params.features.assign(table.feature_columns.size(), params.feature);
  for (const std::string& selector : o.periodic_columns) {
    std::size_t column = 0;
    try {
      column = select_column(selector, table.column_names);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--periodic-columns: ") + e.what());
    }
    const auto it = std::find(table.feature_columns.begin(), table.feature_columns.end(), column);
    if (it == table.feature_columns.end()) {
      // Not a feature: either the label or a column --ignore-columns skips.
      const bool is_label = table.label_column && *table.label_column == column;
      throw std::invalid_argument("--periodic-columns: \"" + selector + "\" is " +
                                  (is_label ? "the label column" : "skipped by --ignore-columns"));
    }
    params.features[static_cast<std::size_t>(it - table.feature_columns.begin())] = periodic;
  }
  return params;
}

PyodParams make_pyod_params(const ScoreOptions& o) {
  PyodParams params;  // PyOD's defaults: 10 bins, alpha 0.1, tol 0.5, contamination 0.1
  if (o.bins) {
    params.auto_bins = o.bins->rule == BinCountRule::BirgeRozenblac;
    if (o.bins->rule == BinCountRule::Fixed) params.n_bins = o.bins->count;
  }
  if (o.alpha) params.alpha = *o.alpha;
  if (o.tol) params.tol = *o.tol;
  if (const auto* c = std::get_if<Contamination>(&o.threshold))
    params.contamination = c->contamination;
  return params;
}

}  // namespace hbos::cli
