#include "fit_command.hpp"

#include <CLI/CLI.hpp>

#include <hbos/merge.hpp>
#include <hbos/model.hpp>
#include <hbos/model_file.hpp>
#include <hbos/pyod/model.hpp>
#include <hbos/pyod/model_file.hpp>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "csv_reader.hpp"
#include "data_matrix.hpp"
#include "npy_reader.hpp"
#include "row_blocks.hpp"

namespace hbos::cli {
namespace {

constexpr int kExitError = 1;
constexpr int kExitBadInput = 2;

struct FitOptions {
  std::string input;
  std::string output;
  std::string mode = "default";
  std::string bins;  // empty: the mode's default
  Eigen::Index shifts = 5;
  std::string binning = "equal-width";
  std::string tail = "both";
  double width = 0.01, origin = 0.0;
  double alpha = 0.1, tol = 0.5, contamination = 0.1;
  bool header = false, no_header = false;
  std::string label_column;
};

/// "auto" -> -1, a count -> itself. \throws std::invalid_argument naming the value.
Eigen::Index parse_count(const std::string& text) {
  std::size_t used = 0;
  long long v = 0;
  try {
    v = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || v < 1)
    throw std::invalid_argument("--bins: '" + text + "' is not a count >= 1 or a rule");
  return static_cast<Eigen::Index>(v);
}

HbosParams default_params(const FitOptions& o) {
  HbosParams p;
  const std::map<std::string, BinningMethod> methods{
      {"equal-width", BinningMethod::EqualWidth},
      {"fixed-width", BinningMethod::FixedWidth},
      {"equal-frequency", BinningMethod::EqualFrequency}};
  const std::map<std::string, BinCountRule> rules{{"sqrt", BinCountRule::Sqrt},
                                                  {"sturges", BinCountRule::Sturges},
                                                  {"scott", BinCountRule::Scott},
                                                  {"fd", BinCountRule::FreedmanDiaconis},
                                                  {"birge", BinCountRule::BirgeRozenblac},
                                                  {"auto", BinCountRule::BirgeRozenblac}};
  const std::map<std::string, Tail> tails{
      {"both", Tail::Both}, {"upper", Tail::Upper}, {"lower", Tail::Lower}};
  p.feature.binning.method = methods.at(o.binning);
  p.feature.binning.shifts = o.shifts;
  p.feature.binning.width = o.width;
  p.feature.binning.origin = o.origin;
  p.feature.tail = tails.at(o.tail);
  if (!o.bins.empty()) {
    const auto rule = rules.find(o.bins);
    if (rule != rules.end()) {
      p.feature.binning.rule = rule->second;
    } else {
      p.feature.binning.bins = parse_count(o.bins);
    }
  }
  return p;
}

PyodParams pyod_params(const FitOptions& o) {
  PyodParams p;
  p.alpha = o.alpha;
  p.tol = o.tol;
  p.contamination = o.contamination;
  if (o.bins == "auto") {
    p.auto_bins = true;
  } else if (!o.bins.empty()) {
    p.n_bins = parse_count(o.bins);
  }
  return p;
}

/// Whether the default-mode fit streams: a CSV file that can be read twice (not standard input,
/// not .npy, which is read whole anyway), bins that need only each feature's range and the row
/// count (hbos/merge.hpp: equal or fixed width with a fixed, sqrt or Sturges count), and a file
/// long for its width. The sharded plan holds a histogram per feature (about 2 KB with its
/// summaries) whatever the rows, the in-memory fit 8 bytes a value: a file of 2 rows x 1e7
/// columns is cheaper read whole (the plan passed 18 GB; the values are 160 MB).
bool streamable(const FitOptions& o, const HbosParams& params, const CsvOptions& csv) {
  // The CLI gives every feature the same spec, so one feature stands for all.
  if (o.input == "-" || is_npy_path(o.input) || !mergeable(params, 1)) return false;
  std::error_code error;
  const auto bytes = std::filesystem::file_size(o.input, error);
  if (error) return false;  // the in-memory path reports what is wrong with the file
  constexpr std::uintmax_t kPlanBytesPerFeature = 2048;
  const auto features = static_cast<std::uintmax_t>(csv_feature_count(o.input, csv));
  return bytes > features * kPlanBytesPerFeature;
}

/// The default-mode fit in two streaming passes over the file (its range, then its counts in
/// the bins that range fixes): bit-identical to Hbos::fit on all the rows (hbos/merge.hpp), in
/// memory bounded by a block of rows, whatever the length of the file.
Hbosd fit_streaming(const std::string& path, const CsvOptions& csv, const HbosParams& params) {
  std::optional<RangeSummary<double>> range;
  for_each_row_block(path, csv, [&](const RowBlock& block) {
    RangeSummary<double> r = summarize_range(block);
    range = range ? merge(*range, r) : std::move(r);
  });
  const ShardedFit<double> plan(*range, params);  // the reader refuses a file without rows
  std::optional<CountSummary> total;
  for_each_row_block(path, csv, [&](const RowBlock& block) {
    CountSummary c = plan.count(block);
    total = total ? merge(*total, c) : std::move(c);
  });
  // A file that changed between the passes no longer matches its range or its row count:
  // ShardedFit refuses the values or the counts then, naming what is wrong.
  return plan.model(*total);
}

/// The default-mode fit of data held in memory, written one feature at a time: each feature's
/// histogram is fitted (by the code Hbos::fit runs for it) and appended to the model file, so
/// only one histogram is held, not one per feature (a fitted Hbos of 1e7 features takes GBs).
/// The file is the one save_model(Hbosd::fit(x, params)) writes.
/// Each column is fitted from rows() contiguous values (gathered from a row-major store), as
/// Hbos::fit reads a column of a column-major matrix, so the bits are the same.
void fit_to_file(const DataMatrix& x, const HbosParams& params, const std::string& path) {
  ModelFileWriter<double> file(path, params, x.cols(), x.rows());
  Histogram<double> histogram;
  std::vector<double> scratch, column;
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    const Eigen::Map<const Eigen::VectorXd> values(x.column(j, column), x.rows());
    histogram.refit(values, params.spec(j), params.scoring, scratch, j);
    file.add(histogram);
  }
  file.commit();
}

/// Whether the PyOD-mode fit of data held in memory goes one feature at a time: a PyodHbos keeps
/// a look-up grid of at least 1024 cells (24 KB) per feature, the feature-by-feature fit about
/// ten doubles per row for the training scores (PyodFeatureScores), so it is the cheaper of the
/// two unless the rows outnumber the features about 200 to 1. Both write the same file.
bool pyod_by_feature(const DataMatrix& x) {
  constexpr Eigen::Index kFeatureBytes = 24 * 1024, kRowBytes = 128;
  return x.rows() <= x.cols() * (kFeatureBytes / kRowBytes);
}

/// The PyOD-mode fit written one feature at a time (PyodModelFileWriter): each column is fitted
/// where it lies in the data (strided in a row-major store, as PyodHbos::fit reads it) and
/// appended to the file; the training scores are summed feature by feature in numpy's order.
/// The file is the one save_model(PyodHbosd::fit(x, params)) writes.
void pyod_fit_to_file(const DataMatrix& x, const PyodParams& params, const std::string& path) {
  PyodModelFileWriter<double> file(path, params, x.cols(), x.rows());
  for (Eigen::Index j = 0; j < x.cols(); ++j)
    file.add(x.data() + j * x.col_stride(), x.row_stride());
  file.commit();
}

}  // namespace

int fit_command(int argc, char** argv) {
  CLI::App app{
      "Fits HBOS on the rows of a CSV or .npy file (rows = samples, columns = features) and saves "
      "the model to a file, for `hbos-score score MODEL DATA`.",
      "hbos-score fit"};
  FitOptions o;
  app.add_option("data", o.input, "CSV file (- = standard input) or .npy file (float64/float32)")
      ->required();
  app.add_option("-o,--output", o.output, "model file to write (atomically)")->required();
  app.add_option("--mode", o.mode, "default (scale-invariant HBOS) or pyod (PyOD 3.6.5's HBOS)")
      ->check(CLI::IsMember({"default", "pyod"}))
      ->capture_default_str();
  app.add_option("--bins", o.bins,
                 "bins per feature: a count, or a rule (default mode: sqrt, sturges, scott, fd, "
                 "birge; pyod: auto). Default 5 (default mode), 10 (pyod)")
      ->type_name("N|RULE");
  app.add_option("--shifts", o.shifts, "default mode: averaged shifted histograms, 1 = plain")
      ->capture_default_str();
  app.add_option("--binning", o.binning, "default mode: equal-width, fixed-width, equal-frequency")
      ->check(CLI::IsMember({"equal-width", "fixed-width", "equal-frequency"}))
      ->capture_default_str();
  app.add_option("--width", o.width, "fixed-width bin width [feature units]")
      ->capture_default_str();
  app.add_option("--origin", o.origin, "an edge of fixed-width bins")->capture_default_str();
  app.add_option("--tail", o.tail, "default mode: both, upper or lower")
      ->check(CLI::IsMember({"both", "upper", "lower"}))
      ->capture_default_str();
  app.add_option("--alpha", o.alpha, "pyod: density regulariser")->capture_default_str();
  app.add_option("--tol", o.tol, "pyod: out-of-range tolerance [bins]")->capture_default_str();
  app.add_option("--contamination", o.contamination,
                 "pyod: share of training outliers (threshold_)")
      ->capture_default_str();
  auto* header = app.add_flag("--header", o.header, "CSV: the first line names the columns");
  app.add_flag("--no-header", o.no_header, "CSV: every line is data")->excludes(header);
  app.add_option("--label-column", o.label_column,
                 "CSV: a 0/1 label column to leave out of the features");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitBadInput;
  }
  try {
    if (hbos::examples::is_same_file(o.output, o.input))
      throw std::invalid_argument("-o '" + o.output + "' is the input file itself: the model " +
                                  "would replace the data");
    CsvOptions csv;
    if (o.header) csv.header = HeaderMode::Present;
    if (o.no_header) csv.header = HeaderMode::Absent;
    csv.label_column = o.label_column;
    Eigen::Index rows = 0, cols = 0;
    // The default mode's parameters (not parsed in the PyOD mode, whose --bins may be "auto").
    const std::optional<HbosParams> params =
        o.mode == "default" ? std::optional<HbosParams>(default_params(o)) : std::nullopt;
    if (params && streamable(o, *params, csv)) {
      const Hbosd model = fit_streaming(o.input, csv, *params);
      rows = model.n_samples();
      cols = model.n_features();
      save_model(model, o.output);
    } else {
      const DataMatrix x = read_data(o.input, csv);
      rows = x.rows();
      cols = x.cols();
      if (o.mode == "pyod") {
        if (pyod_by_feature(x)) {
          pyod_fit_to_file(x, pyod_params(o), o.output);
        } else {
          save_model(PyodHbosd::fit(x.matrix(), pyod_params(o)), o.output);
        }
      } else {
        // Hbos::fit's checks, in its order, before the output is created.
        detail::require(x.rows() > 0, "cannot fit to an empty data set (0 rows)");
        detail::require(x.cols() > 0, "cannot fit to data with no features (0 columns)");
        fit_to_file(x, *params, o.output);
      }
    }
    std::fprintf(stderr, "hbos-score fit: %s model of %lld rows x %lld features written to %s\n",
                 o.mode.c_str(), static_cast<long long>(rows), static_cast<long long>(cols),
                 o.output.c_str());
    return 0;
  } catch (const CsvError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return kExitBadInput;
  } catch (const NpyError& e) {
    std::fprintf(stderr, "hbos-score fit: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    // Data or parameters the model rejects; a model file that cannot be written is reported by
    // the library as InvalidArgument too, naming the path.
    const bool write_error =
        std::string(e.what()).find("cannot write") != std::string::npos ||
        std::string(e.what()).find("cannot create a temporary") != std::string::npos;
    std::fprintf(stderr, "hbos-score fit: error: %s\n", e.what());
    return write_error ? kExitError : kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hbos-score fit: error: %s\n", e.what());
    return kExitError;
  }
}

}  // namespace hbos::cli
