// hbos-score: scores the rows of a numeric CSV or .npy file with HBOS and writes scores, labels and
// (on request) per-feature contributions as CSV.
//
// Exit codes: 0 success; 2 bad options, malformed CSV (reported as file:line:column) or .npy, or
// data the model rejects; 1 anything else (the output cannot be written, out of memory).

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <hbos/version.hpp>

#include <cctype>
#include <cstdio>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "column_selector.hpp"
#include "common/atomic_file.hpp"
#include "common/cli_validators.hpp"
#include "csv_reader.hpp"
#include "fit_command.hpp"
#include "npy_reader.hpp"
#include "results_csv.hpp"
#include "score_command.hpp"
#include "score_input.hpp"
#include "score_options.hpp"
#include "scoring.hpp"
#include "summary.hpp"

namespace {

using namespace hbos::cli;

constexpr int kExitError = 1;
constexpr int kExitBadInput = 2;

/// A CLI11 check that runs one of our parsers and reports its message.
template <class Parse>
CLI::Validator parses_with(Parse parse, const std::string& name) {
  return CLI::Validator(
      [parse](std::string& value) {
        try {
          static_cast<void>(parse(value));
          return std::string();
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
      },
      "", name);
}

/// The raw command line before its values are turned into ScoreOptions.
struct RawOptions {
  std::string delimiter = ",";
  std::string bins;
  std::string threshold = "contamination:0.1";
  std::string periodic_columns;
  std::string binning;
  std::string tail;
  double width = 0.0, origin = 0.0, period_start = 0.0, period = 0.0, alpha = 0.0, tol = 0.0;
  Eigen::Index shifts = 1;
};

/// The keys of a name -> value map, for CLI::IsMember.
template <class Value>
std::vector<std::string> keys_of(const std::map<std::string, Value>& map) {
  std::vector<std::string> names;
  names.reserve(map.size());
  for (const auto& entry : map) names.push_back(entry.first);
  return names;
}

/// CLI::IsMember matched ignoring case but leaves the user's spelling; the maps use lower case.
std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

char parse_delimiter(const std::string& text) {
  if (text == "tab" || text == "\\t") return '\t';
  if (text.size() != 1)
    throw std::invalid_argument("\"" + text + "\" is not one character (or tab)");
  return text[0];
}

int run(const ScoreOptions& options) {
  if (hbos::examples::is_same_file(options.output, options.input))
    throw std::invalid_argument("-o '" + options.output +
                                "' is the input file itself: the scores " +
                                "would replace the data");
  ScoreInput input = read_score_input(options.input, options.csv);
  // The values become the contributions in place: the data is held once, start to end.
  const ScoredTable scored = score_table(options, input, std::move(input.values));
  hbos::examples::AtomicFile output(options.output);
  format_results(scored, input, options.contributions,
                 [&](std::string_view piece) { output.write(piece); });
  output.commit();
  if (!options.quiet) std::fputs(format_summary(options, input, scored).c_str(), stderr);
  return 0;
}

/// Parses the command line and runs; exceptions it does not map to an exit code escape to main.
int score_main(int argc, char** argv) {
  CLI::App app{
      "Scores every row of a numeric CSV or .npy file (rows = samples, columns = features) with "
      "HBOS, the "
      "histogram-based outlier score: higher = more anomalous. Writes CSV with columns score,label "
      "(label 1 = outlier) and, with --contributions, contrib_<feature> per feature; prints a "
      "summary to standard error.",
      "hbos-score"};
  app.footer(
      "Examples:\n"
      "  hbos-score data.csv --label-column label   # default mode, ROC-AUC vs labels\n"
      "  hbos-score data.csv --mode pyod -o out.csv # PyOD 3.6.5's HBOS, number for number\n"
      "  hbos-score - --bins sturges --threshold mad:3 < data.csv\n"
      "  hbos-score data.npy -o out.csv             # numpy.save's float64/float32 arrays\n"
      "Exit codes: 0 success; 2 bad options, malformed CSV (file:line:column) or .npy, or rejected "
      "data; "
      "1 other failures (e.g. the output cannot be written).\n");
  app.set_version_flag("--version", fmt::format("hbos-score {}.{}.{}", hbos::kVersionMajor,
                                                hbos::kVersionMinor, hbos::kVersionPatch));

  ScoreOptions options;
  RawOptions raw;

  app.add_option("input", options.input,
                 "CSV file, - for standard input, or .npy file (float64/float32; 1-D or 2-D)")
      ->required();
  app.add_option("-o,--output", options.output,
                 "result CSV, written atomically (temporary file + rename); - = standard output")
      ->capture_default_str();
  auto* header = app.add_flag("--header", "the first line names the columns (default: detected)");
  auto* no_header = app.add_flag("--no-header", "every line is data")->excludes(header);
  auto* delimiter =
      app.add_option("--delimiter", raw.delimiter, "cell separator: one character or tab")
          ->check(parses_with(parse_delimiter, "CHAR"))
          ->capture_default_str();
  app.add_option("--label-column", options.csv.label_column,
                 "0/1 ground-truth column (1 = outlier), left out of the features; also prints the "
                 "ROC-AUC of the scores against it. A name, a 0-based index or last")
      ->type_name("NAME|INDEX");

  std::string ignore_columns;
  auto* ignore = app.add_option("--ignore-columns", ignore_columns,
                                "comma-separated columns to skip (IDs, an index column); their "
                                "cells need not be numbers")
                     ->type_name("LIST");

  std::string mode = "default";
  app.add_option("--mode", mode,
                 "default: scale-invariant HBOS (5 equal-width bins x 5 shifts unless set below); "
                 "pyod: PyOD 3.6.5's HBOS (10 bins, alpha 0.1, tol 0.5)")
      ->check(CLI::IsMember({"default", "pyod"}, CLI::ignore_case))
      ->capture_default_str();
  const std::map<std::string, hbos::BinningMethod> methods{
      {"equal-width", hbos::BinningMethod::EqualWidth},
      {"fixed-width", hbos::BinningMethod::FixedWidth},
      {"equal-frequency", hbos::BinningMethod::EqualFrequency}};
  auto* binning =
      app.add_option("--binning", raw.binning, "bin edges (default mode; default equal-width)")
          ->check(CLI::IsMember(keys_of(methods), CLI::ignore_case));
  auto* bins =
      app.add_option("--bins", raw.bins,
                     "bins per feature: a count or a rule (sqrt, sturges, scott, fd, birge; "
                     "auto = birge). Default 5 (default mode), 10 (pyod)")
          ->check(parses_with(parse_bins, "N|RULE"))
          ->type_name("N|RULE");
  auto* width =
      app.add_option("--width", raw.width, "bin width for fixed-width binning [feature units]");
  auto* origin = app.add_option("--origin", raw.origin, "an edge of fixed-width bins (default 0)");
  auto* shifts = app.add_option("--shifts", raw.shifts,
                                "averaged shifted histograms: histograms averaged over this many "
                                "shifted origins, 1 = plain histogram (default 5)");
  const std::map<std::string, hbos::Tail> tails{
      {"both", hbos::Tail::Both}, {"upper", hbos::Tail::Upper}, {"lower", hbos::Tail::Lower}};
  auto* tail = app.add_option("--tail", raw.tail,
                              "which side of a feature is anomalous (default mode; default both)")
                   ->check(CLI::IsMember(keys_of(tails), CLI::ignore_case));
  auto* periodic = app.add_option("--periodic-columns", raw.periodic_columns,
                                  "comma-separated columns (names or 0-based indices) holding "
                                  "angles: binned on a circle")
                       ->type_name("LIST");
  auto* period_start = app.add_option("--period-start", raw.period_start,
                                      "start of the period of periodic columns (default -pi)");
  auto* period = app.add_option("--period", raw.period, "length of the period (default 2 pi)");
  auto* alpha =
      app.add_option("--alpha", raw.alpha, "PyOD's density regulariser (pyod mode, default 0.1)");
  auto* tol = app.add_option("--tol", raw.tol,
                             "PyOD's out-of-range tolerance in bins (pyod mode, default 0.5)");
  app.add_option("--threshold", raw.threshold,
                 "outlier cut-off: adaptive[:RANGE_ALPHA] (min + a (max - min), default 0.7), "
                 "contamination[:SHARE] (the (1 - share) quantile, PyOD's rule), mad[:K] (median + "
                 "K robust sigmas, default 3), fixed:VALUE")
      ->check(parses_with(parse_threshold, "RULE"))
      ->capture_default_str();
  app.add_flag("--contributions", options.contributions,
               "also write each feature's contribution to the score (contrib_<feature> columns)");
  app.add_option("--top", options.top, "rows listed in the summary, highest scores first")
      ->check(hbos::examples::non_negative_number())
      ->capture_default_str();
  app.add_flag("-q,--quiet", options.quiet, "no summary on standard error");

  try {
    app.parse(argc, argv);
    if (header->count() > 0) options.csv.header = HeaderMode::Present;
    if (ignore->count() > 0) options.csv.ignore_columns = split_list(ignore_columns);
    if (no_header->count() > 0) options.csv.header = HeaderMode::Absent;
    if (delimiter->count() > 0) options.csv.delimiter = parse_delimiter(raw.delimiter);
    options.mode = lower(mode) == "pyod" ? Mode::Pyod : Mode::Default;
    if (binning->count() > 0) options.binning = methods.at(lower(raw.binning));
    if (bins->count() > 0) options.bins = parse_bins(raw.bins);
    if (width->count() > 0) options.width = raw.width;
    if (origin->count() > 0) options.origin = raw.origin;
    if (shifts->count() > 0) options.shifts = raw.shifts;
    if (tail->count() > 0) options.tail = tails.at(lower(raw.tail));
    if (periodic->count() > 0) options.periodic_columns = split_list(raw.periodic_columns);
    // A file without a header gets its names x<j> when they are printed (CsvLayout::feature_name)
    // rather than one string per column while it is read, unless columns are selected by name.
    options.csv.default_names = !options.periodic_columns.empty();
    if (period_start->count() > 0) options.period_start = raw.period_start;
    if (period->count() > 0) options.period = raw.period;
    if (alpha->count() > 0) options.alpha = raw.alpha;
    if (tol->count() > 0) options.tol = raw.tol;
    options.threshold = parse_threshold(raw.threshold);
    check_combinations(options);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints its own message; its exit codes (105, 106, ...) are folded into ours.
    return app.exit(e) == 0 ? 0 : kExitBadInput;
  } catch (const std::invalid_argument& e) {
    return app.exit(CLI::ValidationError(e.what())) == 0 ? 0 : kExitBadInput;
  }

  try {
    return run(options);
  } catch (const CsvError& e) {
    std::fprintf(stderr, "%s\n", e.what());  // file:line:column: message, as compilers print
    return kExitBadInput;
  } catch (const NpyError& e) {
    std::fprintf(stderr, "hbos-score: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    // hbos::InvalidArgument (data or parameters the model rejects) and our own option checks.
    std::fprintf(stderr, "hbos-score: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const hbos::examples::WriteError& e) {
    std::fprintf(stderr, "hbos-score: error: %s\n", e.what());
    return kExitError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hbos-score: error: %s\n", e.what());
    return kExitError;
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    // Subcommands with model files (fit_command.hpp, score_command.hpp); anything else is the
    // one-shot scorer (a data file named `fit` or `score` is then passed as ./fit).
    const std::string_view command = argc > 1 ? argv[1] : "";
    if (command == "fit") return hbos::cli::fit_command(argc - 1, argv + 1);
    if (command == "score") return hbos::cli::score_command(argc - 1, argv + 1);
    return score_main(argc, argv);
  } catch (const std::exception& e) {  // e.g. out of memory while setting up the parser
    std::fprintf(stderr, "hbos-score: error: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "hbos-score: error: unknown exception\n");
  }
  return kExitError;
}
