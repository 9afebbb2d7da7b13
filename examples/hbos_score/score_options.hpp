#pragma once
/// \file
/// What `hbos-score` was asked to do, the parsers of its option values, and the translation of
/// the options into model parameters. Independent of the command-line library, so it is tested
/// on its own.

#include <hbos/binning.hpp>
#include <hbos/model.hpp>
#include <hbos/pyod.hpp>
#include <hbos/threshold.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "csv_reader.hpp"

namespace hbos::cli {

/// Which scorer: the library's scale-invariant model or the PyOD-compatible one.
enum class Mode {
  Default,  ///< hbos::Hbos with the options below (default: 5 equal-width bins x 5 shifts)
  Pyod      ///< hbos::PyodHbos, PyOD 3.6.5's HBOS number for number
};

/// The value of `--bins`: a count, or a rule that picks the count per feature.
struct BinsChoice {
  BinCountRule rule = BinCountRule::Fixed;
  Eigen::Index count = 0;  ///< for BinCountRule::Fixed
};

/// Every option of hbos-score; an unset optional means "the mode's default".
struct ScoreOptions {
  std::string input;         ///< CSV path, or `-` for standard input
  std::string output = "-";  ///< result path, or `-` for standard output
  CsvOptions csv{};          ///< header mode, delimiter, label column
  Mode mode = Mode::Default;

  // Default mode only.
  std::optional<BinningMethod> binning;
  std::optional<BinsChoice> bins;  ///< also PyOD mode (a count or `auto`)
  std::optional<double> width;     ///< [feature units] fixed-width bins
  std::optional<double> origin;    ///< [feature units] fixed-width bin origin
  std::optional<Eigen::Index> shifts;
  std::optional<Tail> tail;
  std::vector<std::string> periodic_columns;  ///< column selectors (name, index, `last`)
  std::optional<double> period_start;         ///< [feature units] default -pi
  std::optional<double> period;               ///< [feature units] default 2 pi

  // PyOD mode only.
  std::optional<double> alpha;
  std::optional<double> tol;

  ThresholdRule threshold = Contamination{0.1};
  bool contributions = false;  ///< add contrib_<feature> columns to the output
  bool quiet = false;          ///< no summary on standard error
  Eigen::Index top = 5;        ///< rows listed in the summary, highest scores first
};

/// Parses `--bins`: a positive count, or `sqrt`, `sturges`, `scott`, `fd` (Freedman–Diaconis),
/// `birge` (Birgé–Rozenblac; `auto` is a synonym, PyOD's name for it).
/// \throws std::invalid_argument with a message naming the accepted values.
[[nodiscard]] BinsChoice parse_bins(std::string_view text);

/// Parses `--threshold`: `adaptive[:range_alpha]` (default 0.7), `contamination[:share]` (0.1),
/// `mad[:k]` (3), `fixed:value`. Parameters are range-checked here, with the library's limits.
/// \throws std::invalid_argument naming the rule and the accepted range.
[[nodiscard]] ThresholdRule parse_threshold(std::string_view text);

/// `contamination:0.1` etc.: the canonical text of a rule, as parse_threshold reads it.
[[nodiscard]] std::string to_string(const ThresholdRule& rule);
/// `sturges`, `10`, ...
[[nodiscard]] std::string to_string(const BinsChoice& bins);
[[nodiscard]] std::string to_string(BinningMethod method);
[[nodiscard]] std::string to_string(Tail tail);

/// Rejects combinations a per-option check cannot see (an option of the other mode, --width
/// without fixed-width binning, ...).
/// \throws std::invalid_argument naming the options involved.
void check_combinations(const ScoreOptions& options);

/// The default mode's parameters for `table` (periodic columns resolved against its columns).
/// \throws std::invalid_argument when a periodic column is unknown or is the label column.
[[nodiscard]] HbosParams make_params(const ScoreOptions& options, const CsvLayout& table);

/// The PyOD mode's parameters.
[[nodiscard]] PyodParams make_pyod_params(const ScoreOptions& options);

}  // namespace hbos::cli
