#include "score_command.hpp"

#include <CLI/CLI.hpp>

#include <hbos/model_file.hpp>
#include <hbos/pyod/model_file.hpp>

#include <array>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
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

/// Shortest round-trip decimal of `v` (the scores parse back to the same bits).
void append_number(std::string& out, double v) {
  std::array<char, 32> buffer{};
  const auto r = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  out.append(buffer.data(), r.ptr);
}

/// Whether to score `input` with the model read one feature at a time: a file that is short
/// for its width (under 2 KiB per feature, as `fit` decides to read one whole), or a `.npy`
/// file (read whole anyway). A fitted model holds a histogram per feature, about 2 KB each, so
/// for such data the model would cost more memory than the values themselves.
bool score_by_feature(const std::string& input, Eigen::Index n_features) {
  if (input == "-") return false;
  if (is_npy_path(input)) return true;
  std::error_code error;
  const auto bytes = std::filesystem::file_size(input, error);
  if (error) return false;  // the block reader reports what is wrong with the file
  constexpr std::uintmax_t kModelBytesPerFeature = 2048;
  return bytes <= static_cast<std::uintmax_t>(n_features) * kModelBytesPerFeature;
}

/// The scores of the rows of `x`, read whole, by the model file read one feature at a time:
/// each feature's contributions are added in feature order, as Hbos::score adds them, so the
/// scores are load_hbos(path).score(x)'s bit for bit, with one histogram in memory at a time.
Eigen::VectorXd score_by_feature(ModelFileReader<double>& model, const DataMatrix& x) {
  detail::require(x.cols() == model.n_features(), "the model was fitted on ", model.n_features(),
                  " features but the data to score has ", x.cols(), " columns");
  Eigen::VectorXd scores(x.rows());
  std::vector<double> column;
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    const Histogram<double> histogram = model.next();
    histogram.contributions_into(detail::ColumnView<double>{x.column(j, column), x.rows(), 1},
                                 scores.data(), j > 0, j);
  }
  model.finish();
  return scores;
}

/// The PyOD-mode scores of the rows of `x` by the model file read one feature at a time: each
/// feature's log terms are added in numpy's pairwise order over the features
/// (PyodFeatureScores), so the scores are load_pyod_hbos(path).decision_function(x)'s bit for bit,
/// with one feature of the model in memory at a time. `threshold` is set from the file's end.
Eigen::VectorXd pyod_score_by_feature(PyodModelFileReader<double>& model, const DataMatrix& x,
                                      double& threshold) {
  detail::require(x.cols() == model.n_features(), "X has ", x.cols(),
                  " columns but the model was fitted on ", model.n_features(), " features");
  PyodFeatureScores<double> scores(x.cols(), x.rows());
  for (Eigen::Index j = 0; j < x.cols(); ++j)
    scores.add(model.next(), x.data() + j * x.col_stride(), x.row_stride());
  model.finish();
  threshold = model.threshold();
  return scores.scores();
}

/// Whether PyOD-mode scoring of data held in memory goes one feature at a time (see `fit`'s
/// rule: a feature of a loaded PyodHbos takes 24 KB, the scores by feature about ten doubles a
/// row).
bool pyod_by_feature(const DataMatrix& x) {
  constexpr Eigen::Index kFeatureBytes = 24 * 1024, kRowBytes = 128;
  return x.rows() <= x.cols() * (kFeatureBytes / kRowBytes);
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
    for (const std::string& in : {input, model_path}) {
      if (hbos::examples::is_same_file(output, in))
        throw std::invalid_argument("-o '" + output + "' is the input file '" + in +
                                    "' itself: the scores would replace it");
    }
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
    auto write_labelled = [&](double threshold) {
      text = "score,label\n";
      for (Eigen::Index i = 0; i < scores.size(); ++i) {
        append_number(text, scores[i]);
        text += scores[i] > threshold ? ",1\n" : ",0\n";
        write_if_full();
      }
    };
    if (info.kind == "pyod" &&
        score_by_feature(input, PyodModelFileReader<double>(model_path).n_features())) {
      // Data held whole (a file short for its width, or .npy): wide data is scored with the
      // model read one feature at a time, other data with the model loaded whole.
      const DataMatrix x = read_data(input, csv);
      double threshold = 0.0;
      if (pyod_by_feature(x)) {
        PyodModelFileReader<double> model(model_path);
        scores = pyod_score_by_feature(model, x, threshold);
      } else {
        const auto model = load_pyod_hbos<double>(model_path);
        scores = model.decision_function(x.matrix());
        threshold = model.threshold();
      }
      write_labelled(threshold);
    } else if (info.kind == "pyod") {
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
    } else if (ModelFileReader<double> reader(model_path);
               score_by_feature(input, reader.n_features())) {
      scores = score_by_feature(reader, read_data(input, csv));
      text = "score\n";
      for (Eigen::Index i = 0; i < scores.size(); ++i) {
        append_number(text, scores[i]);
        text += '\n';
        write_if_full();
      }
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
