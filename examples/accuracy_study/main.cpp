// hbos-accuracy-study: ROC-AUC of the default mode, classic HBOS variants and the PyOD mode on
// labelled CSV data sets (the 17 ODDS sets), plus the scale test; see docs/accuracy.md.
//
// Exit codes: 0 success (and every requested target met); 1 a target was missed; 2 bad options
// or input.

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "checks.hpp"
#include "column_selector.hpp"
#include "common/atomic_file.hpp"
#include "csv_reader.hpp"
#include "report.hpp"
#include "study.hpp"

namespace {

using namespace hbos;

/// Every `*.csv` of `dir` (or the named subset), sorted by name; the last column is the label.
std::vector<study::DataSet> load_sets(const std::string& dir,
                                      const std::vector<std::string>& only) {
  std::vector<std::filesystem::path> paths;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".csv") continue;
    const std::string stem = entry.path().stem().string();
    if (!only.empty() && std::find(only.begin(), only.end(), stem) == only.end()) continue;
    paths.push_back(entry.path());
  }
  std::sort(paths.begin(), paths.end());
  if (paths.empty()) throw std::invalid_argument("no matching *.csv data sets in " + dir);
  if (!only.empty() && paths.size() != only.size()) {
    throw std::invalid_argument("some of the --sets are not in " + dir);
  }
  std::vector<study::DataSet> sets;
  cli::CsvOptions options;
  options.header = cli::HeaderMode::Present;
  options.label_column = "last";
  for (const auto& path : paths) {
    cli::CsvTable table = cli::read_csv(path.string(), options);
    sets.push_back({path.stem().string(), std::move(table.features), std::move(table.labels)});
  }
  return sets;
}

/// Parses the command line and runs the study; unexpected exceptions escape to main.
int study_main(int argc, char** argv) {
  CLI::App app{
      "ROC-AUC of HBOS configurations (default mode, classic 10 bins, other binnings, PyOD mode) "
      "on "
      "labelled CSV data sets (header row, last column the 0/1 label), fitted on all rows without "
      "scaling, and again with every feature rescaled (and shifted). Prints Markdown tables.",
      "hbos-accuracy-study"};
  std::string dir;
  std::string sets;
  std::uint64_t seed = 1985;
  std::string markdown;
  std::string csv;
  study::Targets targets;
  double published = 0.0;
  app.add_option("--odds-dir", dir, "folder of <name>.csv data sets")
      ->required()
      ->check(CLI::ExistingDirectory);
  app.add_option("--sets", sets, "comma-separated subset of data set names (default: all)");
  app.add_option("--seed", seed, "seed of the rescaling")->capture_default_str();
  app.add_option("--markdown", markdown, "also write the Markdown table here (atomically)");
  app.add_option("--csv", csv, "write every AUC here (atomically), the format --expected reads");
  app.add_option("--expected", targets.expected_csv, "fail unless the AUCs match this --csv output")
      ->check(CLI::ExistingFile);
  app.add_option(
         "--pyod-reference", targets.pyod_reference_csv,
         "fail unless the PyOD mode matches PyOD's AUCs in this file (column roc_auc_default)")
      ->check(CLI::ExistingFile);
  auto* published_option =
      app.add_option("--published-pyod-mean", published,
                     "fail unless the PyOD mode's mean AUC rounds to this (4 decimals)");
  app.add_flag(
      "--check", targets.invariants,
      "fail unless default mean >= PyOD mean, default AUCs survive rescaling and PyOD's do not");
  app.add_option("--tolerance", targets.tolerance, "for --expected and --pyod-reference")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (published_option->count() > 0) targets.published_pyod_mean = published;
  targets.subset = !sets.empty();

  try {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<study::DataSet> data =
        load_sets(dir, sets.empty() ? std::vector<std::string>{} : cli::split_list(sets));
    const double load_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "read %zu data sets in %.2f s\n", data.size(), load_seconds);
    const study::StudyResult result = study::run_study(data, study::study_methods(), seed, stderr);
    std::fprintf(stderr, "fit + score: %.2f s\n", result.seconds.sum());

    const std::string table = study::format_markdown(result, seed);
    std::fputs(table.c_str(), stdout);
    if (!markdown.empty()) examples::write_file_atomically(markdown, table);
    if (!csv.empty()) examples::write_file_atomically(csv, study::format_csv(result));

    const std::vector<std::string> failures = study::check_targets(result, targets);
    for (const std::string& failure : failures)
      std::fprintf(stderr, "FAILED: %s\n", failure.c_str());
    return failures.empty() ? 0 : 1;
  } catch (const cli::CsvError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hbos-accuracy-study: error: %s\n", e.what());
    return 2;
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return study_main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hbos-accuracy-study: error: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "hbos-accuracy-study: error: unknown exception\n");
  }
  return 2;
}
