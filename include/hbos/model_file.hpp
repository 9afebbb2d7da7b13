#pragma once
/// \file
/// Fitted models as files: `save_model(model, path)` and `load_hbos<Scalar>(path)` for the
/// default model `Hbos<Scalar>` (every binning, tail and periodic spec). The PyOD mode has its
/// own pair in hbos/pyod/model_file.hpp; `read_model_info` tells the two apart.
///
/// The format (version 1) is plain text, one `key value...` line each, in a fixed order — the
/// full grammar is in docs/data_science.md. Numbers are written in their shortest decimal form
/// that parses back to the same bits (std::to_chars), so a loaded model scores **bit for bit**
/// like the saved one. Only the fitted histograms' parts are stored (edges, counts, range,
/// shifts, flags; hbos/histogram_parts.hpp): the per-bin contributions are re-derived on load by
/// the code `fit` uses.
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
#include <array>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "hbos/binning.hpp"
#include "hbos/detail/text_format.hpp"
#include "hbos/error.hpp"
#include "hbos/histogram.hpp"
#include "hbos/model.hpp"

namespace hbos {

/// The version of the model file format this library writes and reads.
inline constexpr int kModelFileVersion = 1;

/// What a model file holds, from its first three lines.
struct ModelFileInfo {
  int version = 0;     ///< format version (kModelFileVersion)
  std::string kind;    ///< "hbos" (Hbos, load_hbos) or "pyod" (PyodHbos, load_pyod_hbos)
  std::string scalar;  ///< "double" or "float": the Scalar to load it with
};

namespace detail {

inline constexpr std::array<std::string_view, 3> kMethodNames = {"equal_width", "fixed_width",
                                                                 "equal_frequency"};
inline constexpr std::array<std::string_view, 6> kRuleNames = {
    "fixed", "sqrt", "sturges", "scott", "freedman_diaconis", "birge_rozenblac"};
inline constexpr std::array<std::string_view, 3> kTailNames = {"both", "upper", "lower"};
/// The longest array a model file may declare (edges, counts, training scores).
inline constexpr std::size_t kMaxModelArray = std::size_t{1} << 31;

template <class Scalar>
constexpr std::string_view scalar_name() {
  return std::is_same_v<Scalar, float> ? "float" : "double";
}

/// The first three lines of every model file: magic + version, kind, scalar type.
inline void write_model_header(TextWriter& out, std::string_view kind, std::string_view scalar) {
  out.line("hbos-model-file", kModelFileVersion);
  out.line("kind", kind);
  out.line("scalar", scalar);
}

inline ModelFileInfo read_model_header(TextReader& in) {
  ModelFileInfo info;
  const auto magic = in.expect("hbos-model-file", 1);
  info.version = in.parse<int>("hbos-model-file", magic[0]);
  if (info.version != kModelFileVersion)
    in.fail("hbos-model-file", concat("unsupported format version ", info.version,
                                      " (this library reads version ", kModelFileVersion, ")"));
  info.kind = std::string(in.expect("kind", 1)[0]);
  info.scalar = std::string(in.expect("scalar", 1)[0]);
  if (info.scalar != "double" && info.scalar != "float")
    in.fail("scalar", concat("'", info.scalar, "' is not double or float"));
  return info;
}

/// Reads the header and checks that the file holds a `kind` model of type Scalar.
template <class Scalar>
void expect_model_header(TextReader& in, std::string_view kind, std::string_view loader) {
  const ModelFileInfo info = read_model_header(in);
  if (info.kind != kind)
    throw InvalidArgument(concat(in.source(), ": holds a '", info.kind, "' model, not '", kind,
                                 "' (load it with ",
                                 info.kind == "pyod" ? "load_pyod_hbos" : "load_hbos", ")"));
  if (info.scalar != scalar_name<Scalar>())
    throw InvalidArgument(concat(in.source(), ": holds a ", info.scalar, " model; load it with ",
                                 loader, "<", info.scalar, ">"));
}

inline void write_spec(TextWriter& out, const FeatureSpec& spec) {
  const Binning& b = spec.binning;
  out.line("spec.method", kMethodNames[static_cast<std::size_t>(b.method)]);
  out.line("spec.rule", kRuleNames[static_cast<std::size_t>(b.rule)]);
  out.line("spec.bins", b.bins);
  out.line("spec.width", b.width);
  out.line("spec.origin", b.origin);
  out.line("spec.shifts", b.shifts);
  out.line("spec.max_bins", b.max_bins);
  out.line("spec.tail", kTailNames[static_cast<std::size_t>(spec.tail)]);
  out.line("spec.periodic", spec.periodic);
  out.line("spec.period_start", spec.period_start);
  out.line("spec.period", spec.period);
}

inline FeatureSpec read_spec(TextReader& in, Eigen::Index feature) {
  FeatureSpec spec;
  Binning& b = spec.binning;
  b.method = static_cast<BinningMethod>(in.choice("spec.method", kMethodNames));
  b.rule = static_cast<BinCountRule>(in.choice("spec.rule", kRuleNames));
  b.bins = in.value<Eigen::Index>("spec.bins");
  b.width = in.value<double>("spec.width");
  b.origin = in.value<double>("spec.origin");
  b.shifts = in.value<Eigen::Index>("spec.shifts");
  b.max_bins = in.value<Eigen::Index>("spec.max_bins");
  spec.tail = static_cast<Tail>(in.choice("spec.tail", kTailNames));
  spec.periodic = in.value<bool>("spec.periodic");
  spec.period_start = in.value<double>("spec.period_start");
  spec.period = in.value<double>("spec.period");
  try {
    validate(spec, feature);
  } catch (const InvalidArgument& e) {
    in.fail("spec", message_of(e));
  }
  return spec;
}

template <class Scalar>
void write_parts(TextWriter& out, const HistogramParts<Scalar>& p) {
  out.line("hist.periodic", p.periodic);
  out.line("hist.tail", kTailNames[static_cast<std::size_t>(p.tail)]);
  out.line("hist.uniform", p.uniform);
  out.line("hist.shifts", p.shifts);
  out.line("hist.lo", p.lo);
  out.line("hist.hi", p.hi);
  out.line("hist.inv_width", p.inv_width);
  out.line("hist.period", p.period);
  out.line("hist.scale", p.scale);
  out.line("hist.base", p.base);
  out.array("hist.edges", p.edges);
  out.array("hist.counts", p.counts);
}

template <class Scalar>
HistogramParts<Scalar> read_parts(TextReader& in) {
  HistogramParts<Scalar> p;
  p.periodic = in.value<bool>("hist.periodic");
  p.tail = static_cast<Tail>(in.choice("hist.tail", kTailNames));
  p.uniform = in.value<bool>("hist.uniform");
  p.shifts = in.value<Eigen::Index>("hist.shifts");
  p.lo = in.value<Scalar>("hist.lo");
  p.hi = in.value<Scalar>("hist.hi");
  p.inv_width = in.value<Scalar>("hist.inv_width");
  p.period = in.value<Scalar>("hist.period");
  p.scale = in.value<Scalar>("hist.scale");
  p.base = in.value<Scalar>("hist.base");
  p.edges = in.array<Scalar>("hist.edges", kMaxModelArray);
  p.counts = in.array<Eigen::Index>("hist.counts", kMaxModelArray);
  return p;
}

}  // namespace detail

/// The model as model-file text (see the file comment).
template <class Scalar>
[[nodiscard]] std::string to_model_text(const Hbos<Scalar>& model) {
  detail::TextWriter out;
  detail::write_model_header(out, "hbos", detail::scalar_name<Scalar>());
  const HbosParams& params = model.params();
  out.line("n_features", model.n_features());
  out.line("n_samples", model.n_samples());
  out.line("scoring.empty_bin_count", params.scoring.empty_bin_count);
  out.line("scoring.range_tolerance", params.scoring.range_tolerance);
  out.line("per_feature_specs", !params.features.empty());
  detail::write_spec(out, params.feature);
  for (Eigen::Index j = 0; j < model.n_features(); ++j) {
    out.line("feature", j);
    if (!params.features.empty()) detail::write_spec(out, params.spec(j));
    detail::write_parts(out, model.histogram(j).parts());
    out.line("end");
  }
  return out.text();
}

/// Parses model-file text written by to_model_text / save_model; `source` names it in errors.
/// \throws InvalidArgument naming the source, line and field of the first problem.
template <class Scalar>
[[nodiscard]] Hbos<Scalar> hbos_from_model_text(std::string_view text,
                                                const std::string& source = "model text") {
  detail::TextReader in(text, source);
  detail::expect_model_header<Scalar>(in, "hbos", "load_hbos");
  const auto d = in.value<Eigen::Index>("n_features");
  if (d < 1 || d > (Eigen::Index{1} << 24))
    in.fail("n_features", detail::concat("must lie in [1, 2^24], got ", d));
  const auto n = in.value<Eigen::Index>("n_samples");
  if (n < 1) in.fail("n_samples", detail::concat("must be >= 1, got ", n));
  HbosParams params;
  params.scoring.empty_bin_count = in.value<double>("scoring.empty_bin_count");
  params.scoring.range_tolerance = in.value<double>("scoring.range_tolerance");
  try {
    detail::validate(params.scoring);
  } catch (const InvalidArgument& e) {
    in.fail("scoring", detail::message_of(e));
  }
  const bool per_feature = in.value<bool>("per_feature_specs");
  params.feature = detail::read_spec(in, 0);
  std::vector<HistogramParts<Scalar>> parts;
  std::vector<std::size_t> first_line;
  for (Eigen::Index j = 0; j < d; ++j) {
    const auto index = in.value<Eigen::Index>("feature");
    first_line.push_back(in.line_number());
    if (index != j) in.fail("feature", detail::concat("expected feature ", j, ", got ", index));
    if (per_feature) params.features.push_back(detail::read_spec(in, j));
    parts.push_back(detail::read_parts<Scalar>(in));
    in.expect("end", 0);
  }
  in.expect_end();
  std::vector<Histogram<Scalar>> histograms;
  histograms.reserve(parts.size());
  for (std::size_t j = 0; j < parts.size(); ++j)
    histograms.push_back(Histogram<Scalar>::from_parts(
        std::move(parts[j]), params.scoring,
        detail::concat(source, ", feature ", j, " (from line ", first_line[j], ")")));
  try {
    return Hbos<Scalar>::from_histograms(std::move(histograms), params, n);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(detail::concat(source, ": ", detail::message_of(e)));
  }
}

/// Writes `model` to `path` atomically (see the file comment).
/// \throws InvalidArgument naming the path when it cannot be written.
template <class Scalar>
void save_model(const Hbos<Scalar>& model, const std::string& path) {
  detail::write_file_atomically(path, to_model_text(model));
}

/// Loads a model saved by save_model; it scores bit for bit like the saved one.
/// \throws InvalidArgument naming the file, line and field of a damaged file.
template <class Scalar>
[[nodiscard]] Hbos<Scalar> load_hbos(const std::string& path) {
  return hbos_from_model_text<Scalar>(detail::read_text_file(path),
                                      detail::concat("model file '", path, "'"));
}

/// The version, kind and scalar type of the model file at `path` (its first three lines).
/// \throws InvalidArgument when it is not a model file this library reads.
[[nodiscard]] inline ModelFileInfo read_model_info(const std::string& path) {
  const std::string text = detail::read_text_head(path, 3);
  detail::TextReader in(text, detail::concat("model file '", path, "'"));
  return detail::read_model_header(in);
}

}  // namespace hbos
