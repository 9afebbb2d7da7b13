#pragma once
/// \file
/// Fitted models as files: `save_model(model, path)` and `load_hbos<Scalar>(path)` for the
/// default model `Hbos<Scalar>` (every binning, tail and periodic spec), and, for models too wide
/// to hold as one Hbos, `ModelFileWriter` / `ModelFileReader`, which write and read the same
/// files one feature at a time. The PyOD mode has its own pair in hbos/pyod/model_file.hpp;
/// `read_model_info` tells the two apart.
///
/// The format is plain text, `key value...` lines in a fixed order — the full grammar is in
/// docs/data_science.md. Version 2 (written) stores a feature on one line, uniform edges as the
/// width they were placed with; version 1 (still read) a block of lines per feature. Numbers are
/// written in their shortest decimal form that parses back to the same bits (std::to_chars), so
/// a loaded model scores **bit for bit** like the saved one. Only the fitted histograms' parts
/// are stored (edges, counts, range, shifts; hbos/histogram_parts.hpp): the per-bin
/// contributions are re-derived on load by the code `fit` uses.
///
/// Loading is strict: the magic line, the version, the scalar type, every key in order, every
/// number (finite, in range) and every invariant (edge order, counts >= 0 adding up to
/// n_samples, the specs valid and consistent with the histograms) are checked, and a damaged
/// file gives an InvalidArgument naming the file, the line and the field. Saving is atomic (a
/// temporary file in the same directory, renamed over the target).
///
/// Threading: the functions are reentrant; saving the same path from two threads leaves one of
/// the two complete files.

#include <Eigen/Core>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hbos/binning.hpp"
#include "hbos/detail/model_records.hpp"
#include "hbos/detail/text_format.hpp"
#include "hbos/error.hpp"
#include "hbos/histogram.hpp"
#include "hbos/model.hpp"

namespace hbos {
namespace detail {

/// The lines of a default-mode model before its features: counts, scoring options, the spec.
inline void write_hbos_preamble(TextWriter& out, std::string_view scalar, int version,
                                const HbosParams& params, Eigen::Index n_features,
                                Eigen::Index n_samples) {
  require(version == 1 || version == 2, "model files are written as version 1 or 2, not ", version);
  write_model_header(out, "hbos", scalar, version);
  out.line("n_features", n_features);
  out.line("n_samples", n_samples);
  out.line("scoring.empty_bin_count", params.scoring.empty_bin_count);
  out.line("scoring.range_tolerance", params.scoring.range_tolerance);
  out.line("per_feature_specs", !params.features.empty());
  write_spec(out, params.feature);
}

/// Feature j of a default-mode model in the layout of `version`.
template <class Scalar>
void write_hbos_feature(TextWriter& out, int version, const HbosParams& params, Eigen::Index j,
                        const HistogramParts<Scalar>& parts, std::vector<Scalar>& scratch) {
  if (version == 1) {
    out.line("feature", j);
    if (!params.features.empty()) write_spec(out, params.spec(j));
    write_parts(out, parts);
    out.line("end");
    return;
  }
  if (!params.features.empty()) write_spec_line(out, params.spec(j));
  write_feature_line(out, parts, scratch);
}

/// Reads a default-mode model one feature at a time, from text or a stream (both versions).
template <class Scalar>
class HbosFileReader {
 public:
  explicit HbosFileReader(TextReader& in) : in_(in) {
    version_ = expect_model_header<Scalar>(in, "hbos", "load_hbos").version;
    n_features_ = in.value<Eigen::Index>("n_features");
    if (n_features_ < 1 || n_features_ > (Eigen::Index{1} << 24))
      in.fail("n_features", concat("must lie in [1, 2^24], got ", n_features_));
    n_samples_ = in.value<Eigen::Index>("n_samples");
    if (n_samples_ < 1) in.fail("n_samples", concat("must be >= 1, got ", n_samples_));
    params_.scoring.empty_bin_count = in.value<double>("scoring.empty_bin_count");
    params_.scoring.range_tolerance = in.value<double>("scoring.range_tolerance");
    try {
      validate(params_.scoring);
    } catch (const InvalidArgument& e) {
      in.fail("scoring", message_of(e));
    }
    per_feature_ = in.value<bool>("per_feature_specs");
    params_.feature = read_spec(in, 0);
  }

  [[nodiscard]] int version() const { return version_; }
  [[nodiscard]] Eigen::Index n_features() const { return n_features_; }
  [[nodiscard]] Eigen::Index n_samples() const { return n_samples_; }
  [[nodiscard]] Eigen::Index features_read() const { return next_; }
  /// The parameters; per-feature specs are appended as their features are read.
  [[nodiscard]] const HbosParams& params() const { return params_; }

  /// The next feature's histogram, checked against its spec and the sample count.
  Histogram<Scalar> next() {
    require(next_ < n_features_, in_.source(), ": all ", n_features_, " features were read");
    const Eigen::Index j = next_;
    FeatureSpec spec = params_.feature;
    HistogramParts<Scalar> parts;
    std::size_t first_line = 0;
    if (version_ == 1) {
      const auto index = in_.value<Eigen::Index>("feature");
      first_line = in_.line_number();
      if (index != j) in_.fail("feature", concat("expected feature ", j, ", got ", index));
      if (per_feature_) spec = read_spec(in_, j);
      parts = read_parts<Scalar>(in_);
      in_.expect("end", 0);
    } else {
      if (per_feature_) spec = read_spec_line(in_, j);
      parts = read_feature_line<Scalar>(in_, spec);
      first_line = in_.line_number();
    }
    const std::string where =
        concat(in_.source(), ", feature ", j, " (from line ", first_line, ")");
    // The parts' own invariant first (counts >= 0 before they are added up), then the spec's.
    validate_parts(parts, where);
    try {
      check_against_spec(parts, spec, n_samples_, j);
    } catch (const InvalidArgument& e) {
      throw InvalidArgument(concat(in_.source(), ": ", message_of(e)));
    }
    if (per_feature_) params_.features.push_back(spec);
    ++next_;
    return Histogram<Scalar>::from_parts(std::move(parts), params_.scoring, where);
  }

  /// After the last feature: the end of the file (version 2's `end` line, then blank lines).
  void finish() {
    require(next_ == n_features_, in_.source(), ": ", n_features_ - next_,
            " features were not read");
    if (version_ == 2) in_.expect("end", 0);
    in_.expect_end();
  }

 private:
  TextReader& in_;
  HbosParams params_;
  Eigen::Index n_features_ = 0, n_samples_ = 0, next_ = 0;
  int version_ = 0;
  bool per_feature_ = false;
};

}  // namespace detail

/// The model as model-file text (see the file comment): version 2 unless `version` is 1 (the
/// layout older releases read).
template <class Scalar>
[[nodiscard]] std::string to_model_text(const Hbos<Scalar>& model,
                                        int version = kModelFileVersion) {
  detail::TextWriter out;
  detail::write_hbos_preamble(out, detail::scalar_name<Scalar>(), version, model.params(),
                              model.n_features(), model.n_samples());
  std::vector<Scalar> scratch;
  for (Eigen::Index j = 0; j < model.n_features(); ++j)
    detail::write_hbos_feature(out, version, model.params(), j, model.histogram(j).parts(),
                               scratch);
  if (version == 2) out.line("end");
  return out.text();
}

/// Parses model-file text (version 1 or 2) written by to_model_text / save_model; `source`
/// names it in errors.
/// \throws InvalidArgument naming the source, line and field of the first problem.
template <class Scalar>
[[nodiscard]] Hbos<Scalar> hbos_from_model_text(std::string_view text,
                                                const std::string& source = "model text") {
  detail::TextReader in(text, source);
  detail::HbosFileReader<Scalar> reader(in);
  // Not reserved from the header's n_features: each histogram is read before it is stored.
  std::vector<Histogram<Scalar>> histograms;
  while (reader.features_read() < reader.n_features()) histograms.push_back(reader.next());
  reader.finish();
  try {
    return Hbos<Scalar>::from_histograms(std::move(histograms), reader.params(),
                                         reader.n_samples());
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(detail::concat(source, ": ", detail::message_of(e)));
  }
}

/// Writes `model` to `path` atomically (see the file comment), as format `version` (2 or 1).
/// \throws InvalidArgument naming the path when it cannot be written.
template <class Scalar>
void save_model(const Hbos<Scalar>& model, const std::string& path,
                int version = kModelFileVersion) {
  detail::write_file_atomically(path, to_model_text(model, version));
}

/// Loads a model saved by save_model (version 1 or 2); it scores bit for bit like the saved one.
/// \throws InvalidArgument naming the file, line and field of a damaged file.
template <class Scalar>
[[nodiscard]] Hbos<Scalar> load_hbos(const std::string& path) {
  return hbos_from_model_text<Scalar>(detail::read_text_file(path),
                                      detail::concat("model file '", path, "'"));
}

/// Writes a default-mode model file one feature at a time, for models too wide to hold as one
/// Hbos: memory is one feature's line and a buffer, whatever the feature count. Adding the
/// histograms of `Hbos::fit(x, params)` in feature order, then commit(), writes the very file
/// save_model writes for that model (version 2), atomically: until commit() the path is
/// untouched, and a writer destroyed without commit() leaves no file.
template <class Scalar>
class ModelFileWriter {
 public:
  /// \throws InvalidArgument on invalid parameters or a path that cannot be written.
  ModelFileWriter(const std::string& path, const HbosParams& params, Eigen::Index n_features,
                  Eigen::Index n_samples)
      : file_(path), params_(params), n_features_(n_features), n_samples_(n_samples) {
    detail::require(n_features >= 1 && n_samples >= 1, "a model needs features and samples, got ",
                    n_features, " x ", n_samples);
    detail::validate(params, n_features);
    detail::write_hbos_preamble(out_, detail::scalar_name<Scalar>(), kModelFileVersion, params,
                                n_features, n_samples);
  }

  /// Adds the next feature's histogram, fitted with the spec params.spec(j) gives it, counting
  /// n_samples samples. \throws InvalidArgument naming the feature otherwise.
  void add(const Histogram<Scalar>& histogram) {
    const Eigen::Index j = added_;
    detail::require(j < n_features_, "model file writer: more than ", n_features_, " features");
    const HistogramParts<Scalar> parts = histogram.parts();
    detail::check_against_spec(parts, params_.spec(j), n_samples_, j);
    detail::write_hbos_feature(out_, kModelFileVersion, params_, j, parts, scratch_);
    ++added_;
    if (out_.text().size() >= (std::size_t{1} << 20)) flush();
  }

  /// Completes the file and renames it over the path.
  /// \throws InvalidArgument when features are missing or the file cannot be written.
  void commit() {
    detail::require(added_ == n_features_, "model file writer: ", added_, " of ", n_features_,
                    " features added");
    out_.line("end");
    flush();
    file_.commit();
  }

 private:
  void flush() {
    file_.write(out_.text());
    out_.text().clear();
  }

  detail::AtomicFileWriter file_;
  detail::TextWriter out_;
  HbosParams params_;
  std::vector<Scalar> scratch_;
  Eigen::Index n_features_, n_samples_, added_ = 0;
};

/// Reads a default-mode model file (version 1 or 2) one feature at a time, in one pass over the
/// file: memory is one line, whatever the feature count. Every check load_hbos makes is made,
/// each feature's as it is read and the end of the file by finish().
template <class Scalar>
class ModelFileReader {
 public:
  /// Opens the file and reads everything before the first feature.
  /// \throws InvalidArgument naming the file when it cannot be read or is damaged.
  explicit ModelFileReader(const std::string& path)
      : stream_(std::make_unique<std::ifstream>(path, std::ios::binary)) {
    detail::require(static_cast<bool>(*stream_), "cannot open model file '", path, "'");
    in_ = std::make_unique<detail::TextReader>(*stream_, detail::concat("model file '", path, "'"));
    reader_ = std::make_unique<detail::HbosFileReader<Scalar>>(*in_);
  }

  [[nodiscard]] int version() const { return reader_->version(); }
  [[nodiscard]] Eigen::Index n_features() const { return reader_->n_features(); }
  [[nodiscard]] Eigen::Index n_samples() const { return reader_->n_samples(); }
  /// The scoring options and the spec every feature shares (per-feature specs: params().features
  /// holds those read so far).
  [[nodiscard]] const HbosParams& params() const { return reader_->params(); }
  /// How many features next() has returned.
  [[nodiscard]] Eigen::Index features_read() const { return reader_->features_read(); }

  /// The next feature's histogram: what load_hbos(path).histogram(features_read()) is.
  /// \throws InvalidArgument naming the file, line and field of a damaged feature, or when every
  /// feature has been read.
  [[nodiscard]] Histogram<Scalar> next() { return reader_->next(); }

  /// Checks, after the last feature, that the file ends there.
  void finish() { reader_->finish(); }

 private:
  std::unique_ptr<std::ifstream> stream_;
  std::unique_ptr<detail::TextReader> in_;
  std::unique_ptr<detail::HbosFileReader<Scalar>> reader_;
};

/// The version, kind and scalar type of the model file at `path` (its first three lines).
/// \throws InvalidArgument when it is not a model file this library reads.
[[nodiscard]] inline ModelFileInfo read_model_info(const std::string& path) {
  const std::string text = detail::read_text_head(path, 3);
  detail::TextReader in(text, detail::concat("model file '", path, "'"));
  return detail::read_model_header(in);
}

}  // namespace hbos
