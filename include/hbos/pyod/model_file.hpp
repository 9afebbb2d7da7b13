#pragma once
/// \file
/// The PyOD mode's models as files: `save_model(pyod_model, path)` and
/// `load_pyod_hbos<Scalar>(path)`, in the model-file format of hbos/model_file.hpp (same magic
/// line and versions, `kind pyod`; grammar in docs/data_science.md), and, for models too wide to
/// hold as one PyodHbos, `PyodModelFileWriter` / `PyodModelFileReader`, which write and read the
/// same files one feature at a time.
///
/// Stored: PyOD's parameters (n_bins or `auto`, alpha, tol, contamination), per feature its bin
/// count, range and B_j counts (version 2: one line; the B_j + 1 edges are numpy's edges of that
/// range, rebuilt by the code fit uses; version 1, still read, lists them), the n training scores
/// (`decision_scores_`, one per line, so a loaded model has every attribute PyOD's has) and the
/// threshold (version 2: last, so a writer fitting one feature at a time can write it; version 1:
/// before the features). Densities, look-up tables and labels are re-derived on load by the code
/// `fit` uses, and the edges, counts and threshold are checked against what they imply, so a
/// loaded model scores bit for bit like the saved one and a damaged file is refused, naming the
/// file, line and field. Saving is atomic.

#include <Eigen/Core>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "hbos/detail/text_format.hpp"
#include "hbos/error.hpp"
#include "hbos/model_file.hpp"
#include "hbos/pyod/model.hpp"

namespace hbos {

namespace detail {

/// The lines of a PyOD-mode model before its features.
inline void write_pyod_preamble(TextWriter& out, std::string_view scalar, int version,
                                const PyodParams& p, Eigen::Index n_features,
                                Eigen::Index n_samples) {
  require(version == 1 || version == 2, "model files are written as version 1 or 2, not ", version);
  write_model_header(out, "pyod", scalar, version);
  out.line("n_features", n_features);
  out.line("n_samples", n_samples);
  if (p.auto_bins) {
    out.line("n_bins", "auto");
  } else {
    out.line("n_bins", p.n_bins);
  }
  out.line("alpha", p.alpha);
  out.line("tol", p.tol);
  out.line("contamination", p.contamination);
}

/// Version 2's line of feature j: `f <B> <e_0> <e_B> <c_0> ... <c_{B-1}>`. The edges must be
/// numpy's edges of [e_0, e_B] (true of every fitted or loaded model; checked).
template <class Counts>
void write_pyod_feature_line(TextWriter& out, Eigen::Index j, const Eigen::VectorXd& edges,
                             const Counts& counts) {
  const Eigen::Index B = counts.size();
  require(edges.size() == B + 1 && pyod_bin_edges(j, B, edges[0], edges[B]) == edges, "feature ", j,
          ": the edges are not numpy's edges of their range");
  std::string& line = out.begin_line("f");
  line.push_back(' ');
  append_value(line, static_cast<long long>(B));
  line.push_back(' ');
  append_value(line, edges[0]);
  line.push_back(' ');
  append_value(line, edges[B]);
  for (Eigen::Index k = 0; k < B; ++k) {
    line.push_back(' ');
    append_value(line, static_cast<long long>(counts[k]));
  }
  line.push_back('\n');
}

/// The end of a PyOD-mode model: the training scores, then (version 2) the threshold.
template <class Scalar>
void write_pyod_outputs(TextWriter& out, int version, const Scalar* scores, Eigen::Index n,
                        Scalar threshold) {
  out.line("decision_scores", n);
  for (Eigen::Index i = 0; i < n; ++i) out.bare(scores[i]);
  if (version == 2) out.line("threshold", threshold);
  out.line("end");
}

/// Reads a PyOD-mode model one feature at a time, from text or a stream (both versions).
template <class Scalar>
class PyodFileReader {
 public:
  using Counts = typename PyodHbos<Scalar>::Counts;
  using Vector = typename PyodHbos<Scalar>::Vector;

  explicit PyodFileReader(TextReader& in) : in_(in) {
    version_ = expect_model_header<Scalar>(in, "pyod", "load_pyod_hbos").version;
    d_ = in.value<Eigen::Index>("n_features");
    if (d_ < 1 || d_ > (Eigen::Index{1} << 24))
      in.fail("n_features", concat("must lie in [1, 2^24], got ", d_));
    n_ = in.value<Eigen::Index>("n_samples");
    if (n_ < 1 || static_cast<std::size_t>(n_) > kMaxModelArray)
      in.fail("n_samples", concat("must lie in [1, 2^31], got ", n_));
    // Each parameter is checked as soon as it is read (the others still hold valid defaults),
    // so an error names its own line.
    auto check = [&](std::string_view key) {
      try {
        validate(params_);
      } catch (const InvalidArgument& e) {
        in.fail(key, message_of(e));
      }
    };
    const std::string_view bins = in.expect("n_bins", 1)[0];
    params_.auto_bins = bins == "auto";
    if (!params_.auto_bins) params_.n_bins = in.parse<Eigen::Index>("n_bins", bins);
    check("n_bins");
    params_.alpha = in.value<double>("alpha");
    check("alpha");
    params_.tol = in.value<double>("tol");
    check("tol");
    params_.contamination = in.value<double>("contamination");
    check("contamination");
    if (version_ == 1) {
      threshold_ = in.value<Scalar>("threshold");
      threshold_line_ = in.line_number();
    }
  }

  [[nodiscard]] int version() const { return version_; }
  [[nodiscard]] Eigen::Index n_features() const { return d_; }
  [[nodiscard]] Eigen::Index n_samples() const { return n_; }
  [[nodiscard]] const PyodParams& params() const { return params_; }
  [[nodiscard]] Eigen::Index features_read() const { return next_; }

  /// The next feature's edges and counts as stored (version 2: the edges rebuilt from the
  /// range); `line` is set to the feature's (first) line.
  void next_parts(Eigen::VectorXd& edges, Counts& counts, std::size_t& line) {
    require(next_ < d_, in_.source(), ": all ", d_, " features were read");
    const Eigen::Index j = next_;
    if (version_ == 1) {
      const auto index = in_.value<Eigen::Index>("feature");
      line = in_.line_number();
      if (index != j) in_.fail("feature", concat("expected feature ", j, ", got ", index));
      const auto e = in_.array<double>("edges", kMaxModelArray);
      const auto c = in_.array<Eigen::Index>("counts", kMaxModelArray);
      if (e.size() != c.size() + 1)
        in_.fail("counts",
                 concat(c.size(), " counts for ", e.size(), " edges (needs ", e.size() - 1, ")"));
      edges = Eigen::Map<const Eigen::VectorXd>(e.data(), static_cast<Eigen::Index>(e.size()));
      counts = Eigen::Map<const Counts>(c.data(), static_cast<Eigen::Index>(c.size()));
      in_.expect("end", 0);
    } else {
      const auto t = in_.expect("f");
      line = in_.line_number();
      if (t.size() < 4) in_.fail("f", concat("expected at least 4 values, got ", t.size()));
      const auto B = in_.parse<long long>("f.bins", t[0]);
      if (B < 1 ||
          static_cast<unsigned long long>(B) > static_cast<unsigned long long>(kMaxPyodBins))
        in_.fail("f.bins", concat("bin count ", B, " is outside [1, ", kMaxPyodBins, "]"));
      if (t.size() != static_cast<std::size_t>(B) + 3)
        in_.fail("f", concat("expected ", B + 3, " values for ", B, " bins, got ", t.size()));
      const double lo = in_.parse<double>("f.lo", t[1]);
      const double hi = in_.parse<double>("f.hi", t[2]);
      if (!(lo < hi)) in_.fail("f.hi", concat("the range [", lo, ", ", hi, "] is empty"));
      try {
        edges = pyod_bin_edges(j, static_cast<Eigen::Index>(B), lo, hi);
      } catch (const InvalidArgument& e) {
        in_.fail("f.hi", message_of(e));
      }
      if (edges[0] != lo || edges[B] != hi)
        in_.fail("f.hi", concat("[", lo, ", ", hi, "] is not a range numpy's edges span"));
      counts.resize(static_cast<Eigen::Index>(B));
      for (Eigen::Index k = 0; k < B; ++k)
        counts[k] = in_.parse<Eigen::Index>("f.counts", t[static_cast<std::size_t>(k) + 3]);
    }
    ++next_;
  }

  /// The next feature, checked and rebuilt (PyodFeatureModel::from_parts); errors name its line.
  PyodFeatureModel<Scalar> next() {
    Eigen::VectorXd edges;
    Counts counts;
    std::size_t line = 0;
    next_parts(edges, counts, line);
    try {
      return PyodFeatureModel<Scalar>::from_parts(edges, counts, n_, next_ - 1, params_);
    } catch (const InvalidArgument& e) {
      throw InvalidArgument(concat(in_.source(), ", line ", line, " (",
                                   version_ == 1 ? "counts" : "f", "): ", message_of(e)));
    }
  }

  /// After the last feature: the training scores (returned) and the threshold, checked to be
  /// PyOD's percentile of them; then the end of the file.
  Vector finish() {
    require(next_ == d_, in_.source(), ": ", d_ - next_, " features were not read");
    const auto declared = in_.value<Eigen::Index>("decision_scores");
    if (declared != n_)
      in_.fail("decision_scores", concat(declared, " scores for n_samples = ", n_));
    // Grown as the values are read, not sized by the header: memory follows the file's length,
    // so a damaged n_samples ends in an error naming the short list, not in an allocation.
    std::vector<Scalar> read;
    for (Eigen::Index i = 0; i < n_; ++i) read.push_back(in_.bare<Scalar>("decision_scores"));
    Vector scores = Eigen::Map<const Vector>(read.data(), n_);
    std::vector<Scalar> scratch;
    const Scalar percentile = pyod_threshold(scores.data(), n_, params_.contamination, scratch);
    if (version_ == 2) {
      threshold_ = in_.value<Scalar>("threshold");
      threshold_line_ = in_.line_number();
    }
    if (!(percentile == threshold_))
      throw InvalidArgument(concat(
          in_.source(), ", line ", threshold_line_, " (threshold): ", threshold_,
          " is not the (1 - contamination) percentile ", percentile, " of the training scores"));
    in_.expect("end", 0);
    in_.expect_end();
    finished_ = true;
    return scores;
  }

  /// PyOD's threshold_ (version 1: as stored; both: checked by finish()).
  [[nodiscard]] Scalar threshold() const {
    require(finished_ || version_ == 1, in_.source(), ": the threshold follows the features");
    return threshold_;
  }

 private:
  TextReader& in_;
  PyodParams params_;
  Eigen::Index d_ = 0, n_ = 0, next_ = 0;
  int version_ = 0;
  Scalar threshold_{};
  std::size_t threshold_line_ = 0;
  bool finished_ = false;
};

}  // namespace detail

/// The PyOD-mode model as model-file text (see the file comment): version 2 unless `version` is
/// 1 (the layout older releases read).
template <class Scalar>
[[nodiscard]] std::string to_model_text(const PyodHbos<Scalar>& model,
                                        int version = kModelFileVersion) {
  detail::TextWriter out;
  detail::write_pyod_preamble(out, detail::scalar_name<Scalar>(), version, model.params(),
                              model.n_features(), model.n_samples());
  if (version == 1) out.line("threshold", model.threshold());
  for (Eigen::Index j = 0; j < model.n_features(); ++j) {
    const Eigen::VectorXd& e = model.bin_edges(j);
    const auto& c = model.counts(j);
    if (version == 2) {
      detail::write_pyod_feature_line(out, j, e, c);
      continue;
    }
    out.line("feature", j);
    out.array("edges", std::vector<double>(e.data(), e.data() + e.size()));
    out.array("counts", std::vector<Eigen::Index>(c.data(), c.data() + c.size()));
    out.line("end");
  }
  detail::write_pyod_outputs(out, version, model.decision_scores().data(), model.n_samples(),
                             model.threshold());
  return out.text();
}

/// Parses PyOD-mode model-file text (version 1 or 2); `source` names it in errors.
/// \throws InvalidArgument naming the source, line and field of the first problem.
template <class Scalar>
[[nodiscard]] PyodHbos<Scalar> pyod_hbos_from_model_text(std::string_view text,
                                                         const std::string& source = "model text") {
  detail::TextReader in(text, source);
  detail::PyodFileReader<Scalar> reader(in);
  const auto d = static_cast<std::size_t>(reader.n_features());
  // The reader's errors name the source, line and field; the assembly's are prefixed with it.
  auto assemble = [&source](auto&& build) {
    try {
      return build();
    } catch (const InvalidArgument& e) {
      throw InvalidArgument(detail::concat(source, ": ", detail::message_of(e)));
    }
  };
  if (reader.version() == 2) {
    // Not reserved from the header's n_features: each feature is read before it is stored.
    std::vector<PyodFeatureModel<Scalar>> features;
    for (std::size_t j = 0; j < d; ++j) features.push_back(reader.next());
    auto scores = reader.finish();
    return assemble([&] {
      return PyodHbos<Scalar>::from_features(std::move(features), reader.params(),
                                             std::move(scores));
    });
  }
  std::vector<Eigen::VectorXd> edges;
  std::vector<typename PyodHbos<Scalar>::Counts> counts;
  std::size_t line = 0;
  for (std::size_t j = 0; j < d; ++j) {
    reader.next_parts(edges.emplace_back(), counts.emplace_back(), line);
  }
  auto scores = reader.finish();
  return assemble([&] {
    return PyodHbos<Scalar>::from_parts(edges, counts, reader.params(), std::move(scores));
  });
}

/// Writes the PyOD-mode `model` to `path` atomically, as format `version` (2 or 1).
/// \throws InvalidArgument naming the path when it cannot be written.
template <class Scalar>
void save_model(const PyodHbos<Scalar>& model, const std::string& path,
                int version = kModelFileVersion) {
  detail::write_file_atomically(path, to_model_text(model, version));
}

/// Loads a PyOD-mode model saved by save_model (version 1 or 2); it scores bit for bit like the
/// saved one and has the same decision_scores(), threshold() and labels(). \throws InvalidArgument
/// naming the file, line and field of a damaged file.
template <class Scalar>
[[nodiscard]] PyodHbos<Scalar> load_pyod_hbos(const std::string& path) {
  return pyod_hbos_from_model_text<Scalar>(detail::read_text_file(path),
                                           detail::concat("model file '", path, "'"));
}

/// Fits a PyOD-mode model one feature at a time and writes it to a file as it goes, for models
/// too wide to hold as one PyodHbos (its look-up grid alone takes 24 KB a feature): memory is one
/// feature, a buffer and about ten doubles per training row (the training scores are summed
/// feature by feature in numpy's order, PyodFeatureScores). Adding the columns of X in order,
/// then commit(), writes the very file save_model(PyodHbos::fit(X, params), path) writes
/// (version 2), atomically: until commit() the path is untouched, and a writer destroyed without
/// commit() leaves no file.
template <class Scalar>
class PyodModelFileWriter {
 public:
  /// \throws InvalidArgument on invalid parameters (PyOD's checks) or a path that cannot be
  /// written.
  PyodModelFileWriter(const std::string& path, const PyodParams& params, Eigen::Index n_features,
                      Eigen::Index n_samples)
      : file_(path),
        params_(params),
        scores_(n_features, n_samples),
        terms_(static_cast<std::size_t>(n_samples)) {
    detail::validate(params);
    detail::write_pyod_preamble(out_, detail::scalar_name<Scalar>(), kModelFileVersion, params,
                                n_features, n_samples);
  }

  [[nodiscard]] Eigen::Index n_samples() const { return scores_.rows(); }
  /// Features added so far.
  [[nodiscard]] Eigen::Index features_added() const { return scores_.features_added(); }

  /// Fits the next feature (j = features_added()) on its n_samples() values, `stride` apart, as
  /// PyodHbos::fit fits column j, and appends it. \throws InvalidArgument as fit does (naming
  /// X(i, j)), or when every feature has been added.
  void add(const Scalar* column, Eigen::Index stride) {
    const Eigen::Index j = features_added();
    const PyodFeatureModel<Scalar> feature =
        PyodFeatureModel<Scalar>::fit(column, stride, n_samples(), j, params_, terms_.data());
    scores_.add_terms(terms_.data());  // refuses a feature too many
    detail::write_pyod_feature_line(out_, j, feature.bin_edges(), feature.counts());
    if (out_.text().size() >= (std::size_t{1} << 20)) flush();
  }

  /// The same for a column given as an Eigen vector expression (no copy with direct access).
  template <class Derived>
  void add(const Eigen::DenseBase<Derived>& column) {
    static_assert(std::is_same_v<typename Derived::Scalar, Scalar>,
                  "PyodModelFileWriter<Scalar>::add: the column must hold Scalar values");
    detail::require(column.cols() == 1 && column.rows() == n_samples(), "feature ",
                    features_added(), ": a column of ", n_samples(), " values expected, got ",
                    column.rows(), " x ", column.cols());
    detail::with_strided_view(
        column, [&](const detail::StridedView<Scalar>& v) { add(v.data, v.row_stride); });
  }

  /// Writes the training scores and the threshold, completes the file and renames it over the
  /// path. \throws InvalidArgument when features are missing or the file cannot be written.
  void commit() {
    const auto scores = scores_.scores();  // refuses missing features
    std::vector<Scalar> scratch;
    const Scalar threshold =
        detail::pyod_threshold(scores.data(), scores.size(), params_.contamination, scratch);
    flush();
    // The scores a piece at a time, so the text stays bounded too.
    const Eigen::Index n = scores.size();
    out_.line("decision_scores", n);
    for (Eigen::Index i = 0; i < n; ++i) {
      out_.bare(scores[i]);
      if (out_.text().size() >= (std::size_t{1} << 20)) flush();
    }
    out_.line("threshold", threshold);
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
  PyodParams params_;
  PyodFeatureScores<Scalar> scores_;
  std::vector<double> terms_;
};

/// Reads a PyOD-mode model file (version 1 or 2) one feature at a time, in one pass: memory is
/// one feature and one line, and finish() holds the training scores while it checks the
/// threshold. Every check load_pyod_hbos makes is made, each feature's as it is read (naming its
/// line) and the training scores and threshold by finish().
///
/// Scoring new rows this way gives load_pyod_hbos(path).decision_function(X) bit for bit:
/// \code
///   PyodModelFileReader<double> in(path);
///   PyodFeatureScores<double> scores(in.n_features(), X.rows());
///   for (Eigen::Index j = 0; j < in.n_features(); ++j)
///     scores.add(in.next(), X.col(j).data(), 1);          // X column-major
///   in.finish();
///   Eigen::VectorXd s = scores.scores();   // labels: s[i] > in.threshold()
/// \endcode
template <class Scalar>
class PyodModelFileReader {
 public:
  /// Opens the file and reads everything before the first feature.
  /// \throws InvalidArgument naming the file when it cannot be read or is damaged.
  explicit PyodModelFileReader(const std::string& path)
      : stream_(std::make_unique<std::ifstream>(path, std::ios::binary)) {
    detail::require(static_cast<bool>(*stream_), "cannot open model file '", path, "'");
    in_ = std::make_unique<detail::TextReader>(*stream_, detail::concat("model file '", path, "'"));
    reader_ = std::make_unique<detail::PyodFileReader<Scalar>>(*in_);
  }

  [[nodiscard]] int version() const { return reader_->version(); }
  [[nodiscard]] Eigen::Index n_features() const { return reader_->n_features(); }
  [[nodiscard]] Eigen::Index n_samples() const { return reader_->n_samples(); }
  [[nodiscard]] const PyodParams& params() const { return reader_->params(); }
  /// How many features next() has returned.
  [[nodiscard]] Eigen::Index features_read() const { return reader_->features_read(); }

  /// The next feature: what load_pyod_hbos(path) holds as feature features_read().
  /// \throws InvalidArgument naming the file, line and field of a damaged feature, or when every
  /// feature has been read.
  [[nodiscard]] PyodFeatureModel<Scalar> next() { return reader_->next(); }

  /// After the last feature: reads and checks the training scores and the threshold, and that
  /// the file ends there.
  void finish() { static_cast<void>(reader_->finish()); }

  /// PyOD's threshold_, once finish() has checked it (a version 1 file stores it first).
  [[nodiscard]] Scalar threshold() const { return reader_->threshold(); }

 private:
  std::unique_ptr<std::ifstream> stream_;
  std::unique_ptr<detail::TextReader> in_;
  std::unique_ptr<detail::PyodFileReader<Scalar>> reader_;
};

}  // namespace hbos
