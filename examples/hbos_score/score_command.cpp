#include "score_command.hpp"

#include <CLI/CLI.hpp>

#include <hbos/model_file.hpp>
#include <hbos/pyod/model_file.hpp>

#include <array>
#include <charconv>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "common/atomic_file.hpp"
#include "csv_reader.hpp"
#include "npy_reader.hpp"
#include "row_blocks.hpp"

namespace hbos::cli {
namespace {

constexpr int kExitError = 1;
constexpr int kExitBadInput = 2;

/// Shortest round-trip decimal of `v` (the scores parse back to the same bits).
void append_number(std::string& out, double v) {
  std::array<char, 32> buffer{};
  const auto r = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  out.append(buffer.data(), r.ptr);
}

}  // namespace

int score_command(int argc, char** argv) {
  CLI::App app{
      "Scores the rows of a CSV or .npy file with a model saved by `hbos-score fit` (PyOD's "
      "decision_function): one line per row, `score` (default-mode model) or `score,label` "
      "(PyOD-mode model, label 1 = outlier), with a header line. Higher = more anomalous.",
      "hbos-score score"};
  std::string model_path, input, output = "-", label_column;
  bool header = false, no_header = false;
  app.add_option("model", model_path, "model file written by `hbos-score fit`")->required();
  app.add_option("data", input, "CSV file (- = standard input) or .npy file (float64/float32)")
      ->required();
  app.add_option("-o,--output", output, "scores CSV, written atomically; - = standard output")
      ->capture_default_str();
  auto* header_flag = app.add_flag("--header", header, "CSV: the first line names the columns");
  app.add_flag("--no-header", no_header, "CSV: every line is data")->excludes(header_flag);
  app.add_option("--label-column", label_column, "CSV: a column to leave out of the features");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitBadInput;
  }
  try {
    const ModelFileInfo info = read_model_info(model_path);
    if (info.scalar != "double")
      throw std::invalid_argument("model file '" + model_path + "' holds a " + info.scalar +
                                  " model; hbos-score reads double models");
    CsvOptions csv;
    if (header) csv.header = HeaderMode::Present;
    if (no_header) csv.header = HeaderMode::Absent;
    csv.label_column = label_column;
    // The output is opened first (a path that cannot be written fails before any reading);
    // rows are then read, scored and written a block at a time, so memory stays bounded
    // whatever the length of the file. An error mid-file leaves the output untouched.
    hbos::examples::AtomicFile out(output);
    std::string text;
    auto write_if_full = [&] {
      if (text.size() >= (std::size_t{1} << 20)) {
        out.write(text);
        text.clear();
      }
    };
    Eigen::VectorXd scores;
    if (info.kind == "pyod") {
      const auto model = load_pyod_hbos<double>(model_path);
      text = "score,label\n";
      for_each_row_block(input, csv, [&](const RowBlock& block) {
        scores = model.decision_function(block);
        for (Eigen::Index i = 0; i < scores.size(); ++i) {
          append_number(text, scores[i]);
          text += scores[i] > model.threshold() ? ",1\n" : ",0\n";
        }
        write_if_full();
      });
    } else {
      const auto model = load_hbos<double>(model_path);
      text = "score\n";
      for_each_row_block(input, csv, [&](const RowBlock& block) {
        scores.resize(block.rows());
        model.score_into(block, scores);
        for (Eigen::Index i = 0; i < scores.size(); ++i) {
          append_number(text, scores[i]);
          text += '\n';
        }
        write_if_full();
      });
    }
    out.write(text);
    out.commit();
    return 0;
  } catch (const CsvError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return kExitBadInput;
  } catch (const NpyError& e) {
    std::fprintf(stderr, "hbos-score score: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "hbos-score score: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hbos-score score: error: %s\n", e.what());
    return kExitError;
  }
}

}  // namespace hbos::cli
