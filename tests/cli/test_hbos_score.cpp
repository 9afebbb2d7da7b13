// End-to-end tests of the hbos-score executable: good runs whose output is checked against the
// library, the PyOD mode against PyOD's own numbers, and every malformed input and bad option
// checked for its exit code and message.

#include <hbos/model.hpp>
#include <hbos/model_file.hpp>
#include <hbos/pyod/model_file.hpp>
#include <hbos/threshold.hpp>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/process.hpp"
#include "csv_reader.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kData = HBOS_CLI_TEST_DATA;

using hbos::test::Run;
using hbos::test::slurp;

fs::path work_dir() {
  const fs::path dir = fs::path(HBOS_CLI_WORK_DIR) / "hbos_score_runs";
  fs::create_directories(dir);
  return dir;
}

/// Runs hbos-score with `args`, standard input from `input` (empty: /dev/null). `tag` names the
/// files that capture its output, so concurrently running tests do not share them.
Run hbos_score(const std::string& tag, const std::vector<std::string>& args,
               const std::string& input = "") {
  return hbos::test::run_process(HBOS_SCORE_EXE, args, input.empty() ? "/dev/null" : input,
                                 work_dir() / (tag + ".out"), work_dir() / (tag + ".err"));
}

hbos::cli::CsvTable read_output(const std::string& text) {
  hbos::cli::CsvOptions options;
  options.header = hbos::cli::HeaderMode::Present;
  return hbos::cli::parse_csv(text, "output", options);
}

std::vector<double> read_numbers(const std::string& path) {
  std::ifstream in(path);
  std::vector<double> values;
  double v = 0.0;
  while (in >> v) values.push_back(v);
  return values;
}

}  // namespace

TEST_CASE("hbos-score: a good run, checked against the library", "[cli][hbos_score]") {
  const fs::path output = work_dir() / "good_scores.csv";
  fs::remove(output);
  const Run run = hbos_score("good", {kData + "/good.csv", "--label-column", "label",
                                      "--contributions", "-o", output.string()});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  CHECK(run.out.empty());  // the results went to the file
  CHECK_THAT(run.err, Catch::Contains(
                          "good.csv: 60 rows x 3 features (header detected; label column \"label\" "
                          "excluded)"));
  CHECK_THAT(run.err, Catch::Contains("model: default: equal-width, 5 bins x 5 shifts"));
  CHECK_THAT(run.err, Catch::Contains("threshold: contamination:0.1 -> "));
  CHECK_THAT(run.err, Catch::Contains("outliers: 6 of 60 rows (10.0 %)"));
  CHECK_THAT(run.err,
             Catch::Contains("ROC-AUC against \"label\": 1.0000 (3 labelled outliers; 3 of the 6"));
  CHECK_THAT(run.err, Catch::Contains("top 5 rows by score:\n"));
  for (const char* line : {"line 14 ", "line 32 ", "line 43 "})
    CHECK_THAT(run.err, Catch::Contains(line));

  const auto result = read_output(slurp(output));
  REQUIRE(result.column_names ==
          std::vector<std::string>{"score", "label", "contrib_a", "contrib_b", "contrib_angle"});
  REQUIRE(result.rows() == 60);
  const Eigen::VectorXd scores = result.features.col(0);

  // The same scores as the library, bit for bit (the output round-trips).
  hbos::cli::CsvOptions csv;
  csv.label_column = "label";
  const auto input = hbos::cli::read_csv(kData + "/good.csv", csv);
  const auto model = hbos::Hbosd::fit(input.features);
  CHECK(scores == model.score(input.features));
  CHECK(result.features.rightCols(3) == model.contributions(input.features));

  // Labels are exactly score > the contamination threshold.
  std::vector<double> scratch;
  const double threshold = hbos::compute_threshold(scores, hbos::Contamination{0.1}, scratch);
  for (Eigen::Index i = 0; i < 60; ++i)
    CHECK(result.features(i, 1) == (scores[i] > threshold ? 1.0 : 0.0));
  // The planted outliers (rows 12, 30, 41) score highest and are flagged, each through the
  // feature that was planted: b for row 12, a for row 41.
  std::vector<Eigen::Index> order(60);
  for (Eigen::Index i = 0; i < 60; ++i) order[static_cast<std::size_t>(i)] = i;
  std::sort(order.begin(), order.end(),
            [&](Eigen::Index p, Eigen::Index q) { return scores[p] > scores[q]; });
  std::sort(order.begin(), order.begin() + 3);
  CHECK(order[0] == 12);
  CHECK(order[1] == 30);
  CHECK(order[2] == 41);
  for (const Eigen::Index row : {12, 30, 41}) CHECK(result.features(row, 1) == 1.0);
  CHECK(result.features(12, 3) > result.features(12, 2));
  CHECK(result.features(41, 2) > result.features(41, 3));
}

TEST_CASE("hbos-score: CRLF, quoted names, stdin and stdout give the same bytes",
          "[cli][hbos_score]") {
  const Run file = hbos_score("same_file", {kData + "/good.csv", "--label-column", "label", "-q"});
  const Run crlf =
      hbos_score("same_crlf", {kData + "/good_crlf.csv", "--label-column", "label", "-q"});
  const Run piped =
      hbos_score("same_stdin", {"-", "--label-column", "3", "-q"}, kData + "/good.csv");
  REQUIRE(file.exit_code == 0);
  REQUIRE(crlf.exit_code == 0);
  REQUIRE(piped.exit_code == 0);
  CHECK(file.err.empty());  // --quiet
  CHECK(file.out.rfind("score,label\n", 0) == 0);
  CHECK(std::count(file.out.begin(), file.out.end(), '\n') == 61);
  CHECK(crlf.out == file.out);
  CHECK(piped.out == file.out);
}

TEST_CASE("hbos-score: the PyOD mode reproduces PyOD on ODDS vertebral",
          "[cli][hbos_score][pyod]") {
  const std::string dir = kData + "/pyod_vertebral/";
  const Run run = hbos_score("pyod_vertebral", {dir + "X.csv", "--mode", "pyod"});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  CHECK_THAT(run.err,
             Catch::Contains("240 rows x 6 features (no header (the first line is numeric"));
  CHECK_THAT(run.err,
             Catch::Contains("model: pyod: PyOD 3.6.5 HBOS, n_bins 10, alpha 0.1, tol 0.5"));
  const auto result = read_output(run.out);
  const std::vector<double> scores = read_numbers(dir + "scores.csv");
  const std::vector<double> labels = read_numbers(dir + "labels.csv");
  REQUIRE(result.rows() == 240);
  REQUIRE(scores.size() == 240);
  REQUIRE(labels.size() == 240);
  for (Eigen::Index i = 0; i < 240; ++i) {
    const auto k = static_cast<std::size_t>(i);
    CHECK(result.features(i, 0) == Approx(scores[k]).epsilon(1e-12));
    CHECK(result.features(i, 1) == labels[k]);
  }
  const double threshold = read_numbers(dir + "threshold.txt").at(0);
  char expected[64];
  std::snprintf(expected, sizeof expected, "threshold: contamination:0.1 -> %.6g ", threshold);
  CHECK_THAT(run.err, Catch::Contains(expected));
}

TEST_CASE("hbos-score: other binnings, periodic columns, tails and thresholds run",
          "[cli][hbos_score]") {
  const Run run =
      hbos_score("options", {kData + "/good.csv", "--label-column", "label", "--periodic-columns",
                             "angle", "--tail", "upper", "--bins", "sturges", "--shifts", "3",
                             "--threshold", "mad:2", "--top", "1"});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  CHECK_THAT(
      run.err,
      Catch::Contains("model: default: equal-width, sturges bins x 3 shifts (averaged shifted "
                      "histograms), tail upper; periodic (period 6.28319 from -3.14159): angle"));
  CHECK_THAT(run.err,
             Catch::Contains("bins per feature: 7 for every feature"));  // ceil(log2(60) + 1)
  CHECK_THAT(run.err, Catch::Contains("threshold: mad:2 -> "));
  CHECK_THAT(run.err, Catch::Contains("top 1 rows by score:\n  line 32 "));

  const Run fixed =
      hbos_score("fixed_width", {kData + "/good.csv", "--label-column", "label", "--binning",
                                 "fixed-width", "--width", "2.5", "--threshold", "fixed:4", "-q"});
  REQUIRE(fixed.exit_code == 0);
  const Run frequency =
      hbos_score("equal_frequency", {kData + "/good.csv", "--label-column", "label", "--binning",
                                     "equal-frequency", "--bins", "4"});
  REQUIRE(frequency.exit_code == 0);
  CHECK_THAT(frequency.err, Catch::Contains("model: default: equal-frequency, 4 bins, tail both"));
}

TEST_CASE("hbos-score: ignored columns do not change the scores", "[cli][hbos_score]") {
  // good.csv with an ID column in front, as pandas writes its index.
  const fs::path input = work_dir() / "with_id.csv";
  {
    std::ifstream in(kData + "/good.csv");
    std::ofstream out(input);
    std::string line;
    for (int i = 0; std::getline(in, line); ++i)
      out << (i == 0 ? "id" : "sample-" + std::to_string(i)) << ',' << line << '\n';
  }
  const Run with_id =
      hbos_score("with_id", {input.string(), "--ignore-columns", "id", "--label-column", "label"});
  const Run plain =
      hbos_score("without_id", {kData + "/good.csv", "--label-column", "label", "-q"});
  INFO(with_id.err);
  REQUIRE(with_id.exit_code == 0);
  REQUIRE(plain.exit_code == 0);
  CHECK(with_id.out == plain.out);
  CHECK_THAT(
      with_id.err,
      Catch::Contains("60 rows x 3 features (header detected; label column \"label\" excluded; "
                      "ignored: \"id\")"));
}

TEST_CASE("hbos-score: a header with numeric-looking names is flagged", "[cli][hbos_score]") {
  const fs::path input = work_dir() / "numeric_header.csv";
  { std::ofstream(input) << "speed,2020,2021\n1,2,3\n4,5,6\n7,8,9\n"; }
  const Run run = hbos_score("numeric_header", {input.string()});
  REQUIRE(run.exit_code == 0);
  CHECK_THAT(run.err, Catch::Contains("3 rows x 3 features (header detected)"));
  CHECK_THAT(run.err,
             Catch::Contains("warning: the first line was taken as a header although 2 of its "
                             "cells look numeric; pass --header or --no-header to decide"));
  const Run forced = hbos_score("numeric_header_forced", {input.string(), "--header"});
  REQUIRE(forced.exit_code == 0);
  CHECK_THAT(forced.err, !Catch::Contains("warning"));
}

TEST_CASE("hbos-score: malformed CSV exits 2 with file:line:column", "[cli][hbos_score][errors]") {
  struct Case {
    std::string file;
    std::string position;  // line:column
    std::string message;
    std::vector<std::string> extra_args;
  };
  const std::vector<Case> cases{
      {"empty.csv", "1:1", "empty input: no header and no data rows", {}},
      {"header_only.csv", "2:1", "no data rows after the header", {}},
      {"ragged_short.csv", "4:4", "row has 2 cells but line 1 has 3", {}},
      {"ragged_long.csv", "3:7", "row has 4 cells but line 1 has 3", {}},
      {"ragged_crlf.csv", "3:4", "row has 2 cells but line 1 has 3", {}},
      {"non_numeric.csv", "3:3", "\"five\" is not a number (field 2, \"b\")", {}},
      {"trailing_garbage.csv", "4:5", "\"9x\" is not a number (field 3, \"c\")", {}},
      {"nan.csv",
       "3:5",
       "\"NaN\" is not a finite number (field 3, \"c\"); NaN and infinity are not allowed",
       {}},
      {"inf.csv",
       "3:1",
       "\"-inf\" is not a finite number (field 1, \"a\"); NaN and infinity are not allowed",
       {}},
      {"empty_cell.csv",
       "3:3",
       "empty cell (field 2, \"b\"); missing values are not supported",
       {}},
      {"blank_line.csv",
       "3:1",
       "blank line between rows (only blank lines at the end are ignored)",
       {}},
      {"unterminated_quote.csv",
       "1:3",
       "unterminated quoted cell (a quoted cell cannot span lines)",
       {}},
      {"out_of_range.csv", "3:5", "\"1e999\" is beyond the range of a double (field 3, \"c\")", {}},
      {"bad_label.csv",
       "3:5",
       "label \"0.5\" is neither 0 nor 1 (field 3, \"label\"; 1 marks an outlier)",
       {"--label-column", "label"}},
  };
  // An existing output file must survive a failed run untouched.
  const fs::path output = work_dir() / "kept.csv";
  { std::ofstream(output) << "old\n"; }
  for (const Case& c : cases) {
    const std::string path = kData + "/malformed/" + c.file;
    std::vector<std::string> args{path, "-o", output.string()};
    args.insert(args.end(), c.extra_args.begin(), c.extra_args.end());
    const Run run = hbos_score("malformed_" + c.file, args);
    INFO(c.file << ": " << run.err);
    CHECK(run.exit_code == 2);
    CHECK(run.err == path + ":" + c.position + ": " + c.message + "\n");
  }
  CHECK(slurp(output) == "old\n");

  const Run empty_stdin = hbos_score("malformed_stdin", {"-"});
  CHECK(empty_stdin.exit_code == 2);
  CHECK(empty_stdin.err == "<stdin>:1:1: empty input: no header and no data rows\n");
}

TEST_CASE("hbos-score: bad options exit 2 with a message", "[cli][hbos_score][errors]") {
  const std::string good = kData + "/good.csv";
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases{
      {{}, "input is required"},
      {{good, "--frobnicate"}, "The following argument was not expected: --frobnicate"},
      {{good, "--bins", "0"}, "--bins: \"0\" is neither a bin count in [1, 65536]"},
      {{good, "--bins", "many"}, "--bins: \"many\" is neither a bin count"},
      {{good, "--threshold", "median:3"}, "--threshold: \"median:3\": unknown rule"},
      {{good, "--threshold", "contamination:0.9"}, "contamination must lie in (0, 0.5]"},
      {{good, "--mode", "sklearn"}, "--mode: sklearn not in {default,pyod}"},
      {{good, "--binning", "quantile"}, "--binning: quantile not in"},
      {{good, "--tail", "left"}, "--tail: left not in"},
      {{good, "--shifts", "two"}, "--shifts"},
      {{good, "--header", "--no-header"}, "excludes"},
      {{good, "--delimiter", ";;"}, "\";;\" is not one character (or tab)"},
      {{good, "--mode", "pyod", "--shifts", "2"}, "--shifts is not available with --mode pyod"},
      {{good, "--mode", "pyod", "--bins", "sqrt"}, "--bins sqrt is not available with --mode pyod"},
      {{good, "--alpha", "0.2"}, "--alpha belongs to --mode pyod"},
      {{good, "--binning", "fixed-width"}, "--binning fixed-width needs --width"},
      {{good, "--width", "1"}, "--width applies to --binning fixed-width only"},
      {{good, "--period", "360"}, "--period/--period-start need --periodic-columns"},
      {{good, "--label-column", "truth"}, "label column: no column is named \"truth\""},
      {{good, "--periodic-columns", "heading"},
       "--periodic-columns: no column is named \"heading\""},
      {{good, "--periodic-columns", "a,,b"}, "empty item"},
      {{good, "--label-column", "label", "--periodic-columns", "label"},
       "\"label\" is the label column"},
      {{good, "--ignore-columns", "angle", "--periodic-columns", "angle"},
       "--periodic-columns: \"angle\" is skipped by --ignore-columns"},
      {{good, "--binning", "fixed-width", "--width", "1e-9"}, "more than max_bins"},
  };
  int index = 0;
  for (const Case& c : cases) {
    const Run run = hbos_score("option_" + std::to_string(index++), c.args);
    INFO(run.err);
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.err, Catch::Contains(c.message));
    CHECK(run.out.empty());
  }
}

TEST_CASE("hbos-score: a feature whose range overflows is named once, in both modes",
          "[cli][hbos_score][errors]") {
  // numpy's histogram of [-1e308, 1e308] has bins of width inf: the PyOD mode refuses it and
  // names the feature by index and name, with the library's "hbos: " prefix only once.
  const fs::path csv = work_dir() / "overflowing_range.csv";
  {
    std::ofstream out(csv);
    out << "wide,b\n1e308,2\n-1e308,3\n1,4\n5,5\n";
  }
  const Run pyod = hbos_score("overflow_pyod", {csv.string(), "--mode", "pyod"});
  INFO(pyod.err);
  CHECK(pyod.exit_code == 2);
  CHECK(pyod.out.empty());
  CHECK_THAT(pyod.err, Catch::Contains("hbos-score: error: hbos: feature 0 (\"wide\"): its range "
                                       "[-1e+308, 1e+308] overflows a double"));
  CHECK(pyod.err.find("hbos: ", pyod.err.find("hbos: ") + 1) == std::string::npos);
}

TEST_CASE("hbos-score: help, version and an unwritable output", "[cli][hbos_score]") {
  const Run help = hbos_score("help", {"--help"});
  CHECK(help.exit_code == 0);
  CHECK_THAT(help.out, Catch::Contains("Usage: hbos-score [OPTIONS] input") &&
                           Catch::Contains("Exit codes:"));
  const Run version = hbos_score("version", {"--version"});
  CHECK(version.exit_code == 0);
  CHECK_THAT(version.out, Catch::StartsWith("hbos-score "));

  const Run unwritable =
      hbos_score("unwritable", {kData + "/good.csv", "-o", "/nonexistent/dir/out.csv"});
  CHECK(unwritable.exit_code == 1);
  CHECK_THAT(unwritable.err,
             Catch::Contains("hbos-score: error: cannot create a temporary file next to "
                             "/nonexistent/dir/out.csv"));
}

TEST_CASE("hbos-score fit / score stream a file of many blocks, bit for bit the in-memory fit",
          "[cli][hbos_score][streaming]") {
  // 150,001 rows x 3: three blocks of 65,536 rows and a partial one. `fit` on the file reads it
  // twice in blocks (range, then counts); on standard input it reads it whole. Same model file,
  // byte for byte, and both are Hbos::fit on the parsed rows; `score` streams too, and its
  // scores are the library's, bit for bit (shortest round-trip decimals).
  const fs::path dir = work_dir();
  const fs::path csv = dir / "streaming.csv";
  const Eigen::Index n = 150001;
  {
    std::ofstream out(csv);
    out << "a,b,c\n";
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto k = static_cast<double>(i);
      out << std::sin(k) * 7.0 << ',' << static_cast<double>(i % 97) * 0.5 << ','
          << std::cos(k * 0.37) * 1e-3 << (i == 77777 ? "e4" : "") << '\n';  // one far outlier in c
    }
  }
  for (const std::string bins : {"5", "sturges"}) {
    INFO("bins " << bins);
    const std::string file_model = (dir / ("streaming_file_" + bins + ".hbos")).string();
    const std::string stdin_model = (dir / ("streaming_stdin_" + bins + ".hbos")).string();
    Run r =
        hbos_score("streaming_fit_file", {"fit", csv.string(), "--bins", bins, "-o", file_model});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.err, Catch::Contains("150001 rows x 3 features"));
    r = hbos_score("streaming_fit_stdin", {"fit", "-", "--bins", bins, "-o", stdin_model},
                   csv.string());
    REQUIRE(r.exit_code == 0);
    REQUIRE(slurp(file_model) == slurp(stdin_model));

    const hbos::cli::CsvTable table = hbos::cli::read_csv(csv.string());
    hbos::HbosParams params;
    if (bins == "sturges") params.feature.binning.rule = hbos::BinCountRule::Sturges;
    const hbos::Hbosd direct = hbos::Hbosd::fit(table.features, params);
    const hbos::Hbosd loaded = hbos::load_hbos<double>(file_model);
    const Eigen::VectorXd expected = direct.score(table.features);
    REQUIRE(loaded.score(table.features) == expected);

    const std::string scores = (dir / ("streaming_scores_" + bins + ".csv")).string();
    r = hbos_score("streaming_score", {"score", file_model, csv.string(), "-o", scores});
    REQUIRE(r.exit_code == 0);
    const hbos::cli::CsvTable got = read_output(slurp(scores));
    REQUIRE(got.rows() == n);
    CHECK(got.features.col(0) == expected);
    Eigen::Index top = 0;
    expected.maxCoeff(&top);
    CHECK(top == 77777);
  }
}

TEST_CASE("hbos-score score opens its output before reading and leaves it untouched on bad data",
          "[cli][hbos_score][streaming]") {
  const fs::path dir = work_dir();
  const fs::path good = dir / "score_untouched.csv";
  {
    std::ofstream out(good);
    out << "a,b\n";
    for (int i = 0; i < 100000; ++i) out << i % 13 << ',' << i % 7 << '\n';
    out << "1,oops\n";  // the bad row comes after more than one block
  }
  const std::string model = (dir / "score_untouched.hbos").string();
  {
    std::ofstream small(dir / "small.csv");
    small << "a,b\n1,2\n3,4\n5,7\n";
  }
  Run r = hbos_score("untouched_fit", {"fit", (dir / "small.csv").string(), "-o", model});
  REQUIRE(r.exit_code == 0);
  const fs::path out = dir / "score_untouched_out.csv";
  { std::ofstream(out) << "previous\n"; }
  r = hbos_score("untouched_score", {"score", model, good.string(), "-o", out.string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("score_untouched.csv:100002"));
  CHECK(slurp(out) == "previous\n");
  // An output folder that does not exist fails before the data is read.
  r = hbos_score("untouched_dir",
                 {"score", model, good.string(), "-o", (dir / "no_such_dir" / "x.csv").string()});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, !Catch::Contains("oops"));
}

TEST_CASE("hbos-score fit / score on a wide file: one feature at a time, bit for bit the library",
          "[cli][hbos_score][streaming]") {
  // 3 rows x 3000 columns (a file short for its width): `fit` writes each feature as it is
  // fitted, `score` reads the model one feature at a time. The model is Hbos::fit's, the scores
  // its scores, and the same as `score` from standard input (rows in blocks, the model loaded
  // whole), in every binning.
  const fs::path dir = work_dir();
  const fs::path csv = dir / "wide.csv";
  const Eigen::Index d = 3000;
  {
    std::ofstream out(csv);
    for (int i = 0; i < 3; ++i) {
      for (Eigen::Index j = 0; j < d; ++j)
        out << (j > 0 ? "," : "") << (j % 11 == 5 ? 4.25 : std::sin(double(i * d + j)) * 3.0);
      out << '\n';
    }
  }
  hbos::cli::CsvOptions options;
  options.header = hbos::cli::HeaderMode::Absent;
  const hbos::cli::CsvTable table = hbos::cli::read_csv(csv.string(), options);
  REQUIRE(table.features.cols() == d);
  struct Case {
    std::vector<std::string> args;
    hbos::HbosParams params;
  };
  std::vector<Case> cases(6);
  cases[1].args = {"--bins", "10", "--shifts", "1"};
  cases[1].params.feature.binning.bins = 10;
  cases[1].params.feature.binning.shifts = 1;
  cases[2].args = {"--binning", "equal-frequency", "--bins", "sqrt"};
  cases[2].params.feature.binning.method = hbos::BinningMethod::EqualFrequency;
  cases[2].params.feature.binning.rule = hbos::BinCountRule::Sqrt;
  cases[3].args = {"--binning", "fixed-width", "--width", "0.7", "--origin", "0.1"};
  cases[3].params.feature.binning.method = hbos::BinningMethod::FixedWidth;
  cases[3].params.feature.binning.width = 0.7;
  cases[3].params.feature.binning.origin = 0.1;
  cases[4].args = {"--tail", "upper", "--bins", "scott"};
  cases[4].params.feature.tail = hbos::Tail::Upper;
  cases[4].params.feature.binning.rule = hbos::BinCountRule::Scott;
  cases[5].args = {"--tail", "lower", "--bins", "birge", "--shifts", "2"};
  cases[5].params.feature.tail = hbos::Tail::Lower;
  cases[5].params.feature.binning.rule = hbos::BinCountRule::BirgeRozenblac;
  cases[5].params.feature.binning.shifts = 2;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    INFO("case " << c);
    const std::string model = (dir / ("wide_" + std::to_string(c) + ".hbos")).string();
    std::vector<std::string> args = {"fit", csv.string(), "--no-header", "-o", model};
    args.insert(args.end(), cases[c].args.begin(), cases[c].args.end());
    Run r = hbos_score("wide_fit", args);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const hbos::Hbosd direct = hbos::Hbosd::fit(table.features, cases[c].params);
    CHECK(slurp(model) == hbos::to_model_text(direct));
    const std::string by_feature = (dir / "wide_scores_file.csv").string();
    r = hbos_score("wide_score", {"score", model, csv.string(), "--no-header", "-o", by_feature});
    REQUIRE(r.exit_code == 0);
    const std::string by_rows = (dir / "wide_scores_stdin.csv").string();
    r = hbos_score("wide_score_stdin", {"score", model, "-", "--no-header", "-o", by_rows},
                   csv.string());
    REQUIRE(r.exit_code == 0);
    CHECK(slurp(by_feature) == slurp(by_rows));
    const hbos::cli::CsvTable got = read_output(slurp(by_feature));
    REQUIRE(got.rows() == 3);
    CHECK(got.features.col(0) == direct.score(table.features));
  }
  // A model of another width is refused, naming both counts.
  { std::ofstream(dir / "wide_other.csv") << "1,2\n3,4\n"; }
  const Run r = hbos_score("wide_mismatch", {"score", (dir / "wide_0.hbos").string(),
                                             (dir / "wide_other.csv").string(), "--no-header"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("fitted on 3000 features"));
}

TEST_CASE("hbos-score fit / score --mode pyod on a wide file: one feature at a time, bit for bit",
          "[cli][hbos_score][streaming][pyod]") {
  // 5 rows x 3000 columns: the PyOD-mode `fit` fits and writes one feature at a time
  // (PyodModelFileWriter), `score` reads the model one feature at a time and sums each row's
  // terms in numpy's pairwise order. The model file is save_model(PyodHbos::fit)'s, version 2;
  // the scores and labels are the library's and those of `score` from standard input (blocks of
  // rows, the model loaded whole).
  const fs::path dir = work_dir();
  const fs::path csv = dir / "wide_pyod.csv";
  const Eigen::Index d = 3000;
  {
    std::ofstream out(csv);
    for (int i = 0; i < 5; ++i) {
      for (Eigen::Index j = 0; j < d; ++j)
        out << (j > 0 ? "," : "") << (j % 13 == 4 ? 1.5 : std::cos(double(i * d + j)) * 7.0);
      out << '\n';
    }
  }
  hbos::cli::CsvOptions options;
  options.header = hbos::cli::HeaderMode::Absent;
  const hbos::cli::CsvTable table = hbos::cli::read_csv(csv.string(), options);
  REQUIRE(table.features.cols() == d);
  struct Case {
    std::vector<std::string> args;
    hbos::PyodParams params;
  };
  std::vector<Case> cases(3);
  cases[1].args = {"--bins", "5", "--alpha", "0.05", "--tol", "0.3", "--contamination", "0.2"};
  cases[1].params.n_bins = 5;
  cases[1].params.alpha = 0.05;
  cases[1].params.tol = 0.3;
  cases[1].params.contamination = 0.2;
  cases[2].args = {"--bins", "auto"};
  cases[2].params.auto_bins = true;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    INFO("case " << c);
    const std::string model = (dir / ("wide_pyod_" + std::to_string(c) + ".hbos")).string();
    std::vector<std::string> args = {"fit",  csv.string(), "--no-header", "--mode",
                                     "pyod", "-o",         model};
    args.insert(args.end(), cases[c].args.begin(), cases[c].args.end());
    Run r = hbos_score("wide_pyod_fit", args);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const hbos::PyodHbosd direct = hbos::PyodHbosd::fit(table.features, cases[c].params);
    const std::string text = slurp(model);
    CHECK(text.rfind("hbos-model-file 2\nkind pyod\n", 0) == 0);
    CHECK(text == hbos::to_model_text(direct));
    const std::string by_feature = (dir / "wide_pyod_scores_file.csv").string();
    r = hbos_score("wide_pyod_score",
                   {"score", model, csv.string(), "--no-header", "-o", by_feature});
    REQUIRE(r.exit_code == 0);
    const std::string by_rows = (dir / "wide_pyod_scores_stdin.csv").string();
    r = hbos_score("wide_pyod_score_stdin", {"score", model, "-", "--no-header", "-o", by_rows},
                   csv.string());
    REQUIRE(r.exit_code == 0);
    CHECK(slurp(by_feature) == slurp(by_rows));
    const hbos::cli::CsvTable got = read_output(slurp(by_feature));
    REQUIRE(got.rows() == 5);
    CHECK(got.features.col(0) == direct.decision_function(table.features));
    CHECK(got.features.col(1).cast<int>() == direct.predict(table.features));
    // A version 1 file of the same model (written before 2026-12-03) scores the same bytes.
    const std::string v1 = (dir / "wide_pyod_v1.hbos").string();
    hbos::save_model(direct, v1, 1);
    const std::string from_v1 = (dir / "wide_pyod_scores_v1.csv").string();
    r = hbos_score("wide_pyod_score_v1", {"score", v1, csv.string(), "--no-header", "-o", from_v1});
    REQUIRE(r.exit_code == 0);
    CHECK(slurp(from_v1) == slurp(by_feature));
  }
  // A damaged feature line is refused naming the file, the line and the field.
  std::string damaged = slurp(dir / "wide_pyod_0.hbos");
  const std::size_t f = damaged.find("\nf 10 ") + 6;
  damaged.insert(f, "x");
  { std::ofstream(dir / "wide_pyod_damaged.hbos", std::ios::binary) << damaged; }
  const Run r = hbos_score("wide_pyod_damaged", {"score", (dir / "wide_pyod_damaged.hbos").string(),
                                                 csv.string(), "--no-header"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("wide_pyod_damaged.hbos', line 10 (f.lo): 'x"));
}

TEST_CASE("hbos-score: the one-shot form of a file without a header names its columns x<j>",
          "[cli][hbos_score]") {
  // The names are made when printed, not kept per column; the output and summary name the
  // columns as before, a made-up name still selects a periodic column, and the PyOD-mode scores
  // (each feature fitted on its own, without a look-up grid for 3 rows) are the library's.
  const fs::path dir = work_dir();
  const fs::path csv = dir / "unnamed.csv";
  Eigen::MatrixXd x(3, 12);
  {
    std::ofstream out(csv);
    for (Eigen::Index i = 0; i < x.rows(); ++i) {
      for (Eigen::Index j = 0; j < x.cols(); ++j) {
        x(i, j) = static_cast<double>((i * 7 + j * 3) % 10);
        out << (j > 0 ? "," : "") << x(i, j);
      }
      out << '\n';
    }
  }
  std::vector<std::string> expected_names = {"score", "label"};
  for (int j = 0; j < 12; ++j) expected_names.push_back("contrib_x" + std::to_string(j));
  const fs::path output = dir / "unnamed_scores.csv";
  // Auto bins need more than 3 rows: the error names the first column by its made-up name.
  const Run refused = hbos_score(
      "unnamed_auto", {csv.string(), "--mode", "pyod", "--bins", "auto", "-o", output.string()});
  CHECK(refused.exit_code != 0);
  CHECK_THAT(refused.err, Catch::Contains("feature 0 (\"x0\")"));
  for (const bool pyod : {false, true}) {
    std::vector<std::string> args = {csv.string(), "--contributions", "-o", output.string()};
    if (pyod) args.insert(args.end(), {"--mode", "pyod"});
    const Run run = hbos_score("unnamed", args);
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    CHECK_THAT(run.err, Catch::Contains("largest contributions: x"));
    const auto result = read_output(slurp(output));
    CHECK(result.column_names == expected_names);
    if (pyod) {
      const Eigen::VectorXd scores = result.features.col(0);
      CHECK(scores == hbos::PyodHbosd::fit(x).decision_scores());
    }
  }
  const Run periodic = hbos_score(
      "unnamed_periodic", {csv.string(), "--periodic-columns", "x3", "-q", "-o", output.string()});
  INFO(periodic.err);
  CHECK(periodic.exit_code == 0);
}

TEST_CASE("hbos-score: -o naming an input file is refused, the input kept", "[cli][hbos_score]") {
  const fs::path data = work_dir() / "own_output.csv";
  fs::copy_file(kData + "/good.csv", data, fs::copy_options::overwrite_existing);
  const std::string before = slurp(data);
  // The scorer, `fit` and `score`: each would have replaced its input.
  const Run scored = hbos_score("own_output_score", {data.string(), "-o", data.string()});
  CHECK(scored.exit_code == 2);
  CHECK_THAT(scored.err, Catch::Contains("is the input file itself"));
  const Run fitted = hbos_score("own_output_fit", {"fit", data.string(), "-o", data.string()});
  CHECK(fitted.exit_code == 2);
  CHECK_THAT(fitted.err, Catch::Contains("is the input file itself"));
  const fs::path model = work_dir() / "own_output.hbos";
  REQUIRE(hbos_score("own_output_model", {"fit", data.string(), "-o", model.string()}).exit_code ==
          0);
  for (const fs::path& target : {data, model}) {
    const Run r = hbos_score("own_output_score_model",
                             {"score", model.string(), data.string(), "-o", target.string()});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("itself: the scores would replace it"));
  }
  CHECK(slurp(data) == before);
}

namespace {

// A version 1.0 .npy file of `values` (float64, C order) with `header` as its dict, padded as
// numpy pads it.
void write_npy(const fs::path& path, std::string header, const std::vector<double>& values) {
  const std::size_t unpadded = 10 + header.size() + 1;
  header.append((64 - unpadded % 64) % 64, ' ');
  header += '\n';
  std::ofstream out(path, std::ios::binary);
  out.write("\x93NUMPY\x01\x00", 8);
  const auto length = static_cast<std::uint16_t>(header.size());
  const char length_bytes[2] = {static_cast<char>(length & 0xFF), static_cast<char>(length >> 8)};
  out.write(length_bytes, 2);
  out << header;
  out.write(reinterpret_cast<const char*>(values.data()),
            static_cast<std::streamsize>(values.size() * sizeof(double)));
}

}  // namespace

TEST_CASE(
    "hbos-score: .npy headers as other writers space them, duplicate keys, the suffix in any case",
    "[cli][hbos_score]") {
  const std::vector<double> values = {0.1, 1.0, 0.2, 1.1, 0.15, 5.0};  // 3 rows x 2 features
  const fs::path spaced = work_dir() / "spaced.npy";
  write_npy(spaced, "{ 'shape' : ( 3 , 2 ) , 'fortran_order' : False , 'descr' : '<f8' }", values);
  const Run a = hbos_score("npy_spaced", {spaced.string(), "-o", "-"});
  CHECK(a.exit_code == 0);
  CHECK_THAT(a.err, Catch::Contains("3 rows x 2 features (.npy array)"));
  // numpy would take the last of two 'descr'; which one the writer meant is not knowable.
  const fs::path twice = work_dir() / "twice.npy";
  write_npy(twice, "{'descr': '<f4', 'fortran_order': False, 'shape': (3, 2), 'descr': '<f8', }",
            values);
  const Run b = hbos_score("npy_twice", {twice.string(), "-o", "-"});
  CHECK(b.exit_code == 2);
  CHECK_THAT(b.err, Catch::Contains("names 'descr' twice"));
  // x.NPY was parsed as CSV; a .npy without its suffix too.
  for (const char* name : {"upper.NPY", "no_suffix"}) {
    const fs::path other = work_dir() / name;
    fs::copy_file(spaced, other, fs::copy_options::overwrite_existing);
    const Run r = hbos_score(std::string("npy_") + name, {other.string(), "-o", "-"});
    CHECK(r.exit_code == 0);
    CHECK(r.out == a.out);
  }
}
