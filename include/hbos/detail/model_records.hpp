#pragma once
/// \file
/// The records of model files (hbos/model_file.hpp, hbos/pyod/model_file.hpp): the three header
/// lines every file starts with, the spec block, and a default-mode feature in either layout —
/// version 1's block of `hist.*` lines, or version 2's single line per feature (its bins' flags
/// follow from the feature's spec, and uniform edges are stored as the one width they were
/// placed with). The grammar of both is in docs/data_science.md.

#include <Eigen/Core>
#include <array>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "hbos/binning.hpp"
#include "hbos/detail/text_format.hpp"
#include "hbos/error.hpp"
#include "hbos/histogram_parts.hpp"

namespace hbos {

/// The version of the model file format this library writes, for the default model (Hbos) and
/// the PyOD mode (PyodHbos) alike. It reads versions 1 and 2 of both.
inline constexpr int kModelFileVersion = 2;

/// What a model file holds, from its first three lines.
struct ModelFileInfo {
  int version = 0;     ///< format version (1 or 2)
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
inline void write_model_header(TextWriter& out, std::string_view kind, std::string_view scalar,
                               int version) {
  out.line("hbos-model-file", version);
  out.line("kind", kind);
  out.line("scalar", scalar);
}

inline ModelFileInfo read_model_header(TextReader& in) {
  ModelFileInfo info;
  const auto magic = in.expect("hbos-model-file", 1);
  info.version = in.parse<int>("hbos-model-file", magic[0]);
  if (info.version < 1 || info.version > kModelFileVersion)
    in.fail("hbos-model-file",
            concat("unsupported format version ", info.version,
                   " (this library reads versions 1 to ", kModelFileVersion, ")"));
  info.kind = std::string(in.expect("kind", 1)[0]);
  info.scalar = std::string(in.expect("scalar", 1)[0]);
  if (info.scalar != "double" && info.scalar != "float")
    in.fail("scalar", concat("'", info.scalar, "' is not double or float"));
  return info;
}

/// Reads the header and checks that the file holds a `kind` model of type Scalar.
template <class Scalar>
ModelFileInfo expect_model_header(TextReader& in, std::string_view kind, std::string_view loader) {
  ModelFileInfo info = read_model_header(in);
  if (info.kind != kind)
    throw InvalidArgument(concat(in.source(), ": holds a '", info.kind, "' model, not '", kind,
                                 "' (load it with ",
                                 info.kind == "pyod" ? "load_pyod_hbos" : "load_hbos", ")"));
  if (info.scalar != scalar_name<Scalar>())
    throw InvalidArgument(concat(in.source(), ": holds a ", info.scalar, " model; load it with ",
                                 loader, "<", info.scalar, ">"));
  return info;
}

/// The spec's fields in file order (a block of `spec.*` lines, or one `spec` line).
template <class Emit>
void for_each_spec_field(const FeatureSpec& spec, const Emit& emit) {
  const Binning& b = spec.binning;
  emit("spec.method", kMethodNames[static_cast<std::size_t>(b.method)]);
  emit("spec.rule", kRuleNames[static_cast<std::size_t>(b.rule)]);
  emit("spec.bins", b.bins);
  emit("spec.width", b.width);
  emit("spec.origin", b.origin);
  emit("spec.shifts", b.shifts);
  emit("spec.max_bins", b.max_bins);
  emit("spec.tail", kTailNames[static_cast<std::size_t>(spec.tail)]);
  emit("spec.periodic", spec.periodic);
  emit("spec.period_start", spec.period_start);
  emit("spec.period", spec.period);
}

inline void write_spec(TextWriter& out, const FeatureSpec& spec) {
  for_each_spec_field(spec, [&](std::string_view key, const auto& v) { out.line(key, v); });
}

/// The spec as one line, `spec <the 11 fields>` (version 2's per-feature specs).
inline void write_spec_line(TextWriter& out, const FeatureSpec& spec) {
  std::string line = "spec";
  for_each_spec_field(spec, [&](std::string_view, const auto& v) {
    line.push_back(' ');
    if constexpr (std::is_convertible_v<decltype(v), std::string_view>) {
      line.append(std::string_view(v));
    } else {
      append_value(line, v);
    }
  });
  out.raw_line(line);
}

/// Reads a spec field by field; `next(key)` gives the token of field `key`.
template <class Next>
FeatureSpec parse_spec(TextReader& in, Eigen::Index feature, const Next& next) {
  auto choice = [&](std::string_view key, const auto& names) {
    const std::string_view token = next(key);
    for (std::size_t i = 0; i < names.size(); ++i)
      if (token == names[i]) return i;
    std::string allowed;
    for (std::size_t i = 0; i < names.size(); ++i) allowed += concat(i > 0 ? ", " : "", names[i]);
    in.fail(key, concat("'", token, "' is not one of ", allowed));
  };
  FeatureSpec spec;
  Binning& b = spec.binning;
  b.method = static_cast<BinningMethod>(choice("spec.method", kMethodNames));
  b.rule = static_cast<BinCountRule>(choice("spec.rule", kRuleNames));
  b.bins = in.parse<Eigen::Index>("spec.bins", next("spec.bins"));
  b.width = in.parse<double>("spec.width", next("spec.width"));
  b.origin = in.parse<double>("spec.origin", next("spec.origin"));
  b.shifts = in.parse<Eigen::Index>("spec.shifts", next("spec.shifts"));
  b.max_bins = in.parse<Eigen::Index>("spec.max_bins", next("spec.max_bins"));
  spec.tail = static_cast<Tail>(choice("spec.tail", kTailNames));
  spec.periodic = in.parse<bool>("spec.periodic", next("spec.periodic"));
  spec.period_start = in.parse<double>("spec.period_start", next("spec.period_start"));
  spec.period = in.parse<double>("spec.period", next("spec.period"));
  try {
    validate(spec, feature);
  } catch (const InvalidArgument& e) {
    in.fail("spec", message_of(e));
  }
  return spec;
}

/// A block of `spec.*` lines.
inline FeatureSpec read_spec(TextReader& in, Eigen::Index feature) {
  std::string token;  // the line's value, copied: the next line may replace the reader's buffer
  return parse_spec(in, feature, [&](std::string_view key) {
    token = std::string(in.expect(key, 1)[0]);
    return std::string_view(token);
  });
}

/// One `spec` line.
inline FeatureSpec read_spec_line(TextReader& in, Eigen::Index feature) {
  const auto tokens = in.expect("spec", 11);
  std::size_t i = 0;
  return parse_spec(in, feature, [&](std::string_view) { return tokens[i++]; });
}

/// Version 1: a feature's parts as `hist.*` lines.
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

/// Whether the parts' edges are exactly the uniform ones of their `fine` width (so version 2
/// stores that width instead of them), and inv_width its inverse as placement computes it.
template <class Scalar>
bool edges_from_fine(const HistogramParts<Scalar>& p, std::vector<Scalar>& scratch) {
  const auto k = static_cast<Eigen::Index>(p.counts.size());
  if (!p.uniform || !(p.fine > Scalar(0) || k == 1) ||
      p.inv_width != (p.fine > Scalar(0) ? Scalar(1) / p.fine : Scalar(0)) ||
      p.edges.size() != p.counts.size() + 1)
    return false;
  fill_uniform_edges(p.lo, p.hi, p.scale, p.base, p.fine, k, scratch);
  return std::memcmp(scratch.data(), p.edges.data(), p.edges.size() * sizeof(Scalar)) == 0;
}

/// Version 2: a feature's parts as one line (see the file comment),
///   f <lo> <hi> <inv_width> <period> <scale> <base> <k> u <fine> <c_0> ... <c_{k-1}>
///   f <lo> <hi> <inv_width> <period> <scale> <base> <k> e <e_0> ... <e_k> <c_0> ... <c_{k-1}>
/// `scratch` is reused across calls.
template <class Scalar>
void write_feature_line(TextWriter& out, const HistogramParts<Scalar>& p,
                        std::vector<Scalar>& scratch) {
  std::string& line = out.begin_line("f");
  for (const Scalar v : {p.lo, p.hi, p.inv_width, p.period, p.scale, p.base}) {
    line.push_back(' ');
    append_value(line, v);
  }
  line.push_back(' ');
  append_value(line, static_cast<long long>(p.counts.size()));
  if (edges_from_fine(p, scratch)) {
    line.append(" u ");
    append_value(line, p.fine);
  } else {
    line.append(" e");
    for (const Scalar e : p.edges) {
      line.push_back(' ');
      append_value(line, e);
    }
  }
  for (const Eigen::Index c : p.counts) {
    line.push_back(' ');
    append_value(line, static_cast<long long>(c));
  }
  line.push_back('\n');
}

/// Reads a version 2 feature line; the flags (periodic, tail, uniform, shifts) come from the
/// feature's spec, as Hbos::from_histograms requires of them.
template <class Scalar>
HistogramParts<Scalar> read_feature_line(TextReader& in, const FeatureSpec& spec) {
  const auto t = in.expect("f");
  if (t.size() < 9) in.fail("f", concat("expected at least 9 values, got ", t.size()));
  HistogramParts<Scalar> p;
  const bool equal_frequency = spec.binning.method == BinningMethod::EqualFrequency;
  p.periodic = spec.periodic;
  p.tail = spec.tail;
  p.uniform = spec.periodic || !equal_frequency;
  p.shifts = equal_frequency ? 1 : spec.binning.shifts;
  p.lo = in.parse<Scalar>("f.lo", t[0]);
  p.hi = in.parse<Scalar>("f.hi", t[1]);
  p.inv_width = in.parse<Scalar>("f.inv_width", t[2]);
  p.period = in.parse<Scalar>("f.period", t[3]);
  p.scale = in.parse<Scalar>("f.scale", t[4]);
  p.base = in.parse<Scalar>("f.base", t[5]);
  const auto k = in.parse<long long>("f.bins", t[6]);
  if (k < 1 || static_cast<unsigned long long>(k) >= kMaxModelArray)
    in.fail("f.bins", concat("bin count ", k, " is outside [1, ", kMaxModelArray - 1, "]"));
  const auto bins = static_cast<std::size_t>(k);
  const std::string_view form = t[7];
  std::size_t next = 8;
  if (form == "u") {
    if (t.size() != 9 + bins)
      in.fail("f", concat("uniform bins: expected ", 9 + bins, " values for ", bins, " bins, got ",
                          t.size()));
    p.fine = in.parse<Scalar>("f.fine", t[next++]);
    if (!p.uniform) in.fail("f.fine", "the spec's bins are not uniform: edges must be listed");
    if (!(p.fine > Scalar(0) || bins == 1) ||
        p.inv_width != (p.fine > Scalar(0) ? Scalar(1) / p.fine : Scalar(0)))
      in.fail("f.fine", concat("width ", p.fine, " does not match inv_width ", p.inv_width, " and ",
                               bins, " bins"));
    fill_uniform_edges(p.lo, p.hi, p.scale, p.base, p.fine, k, p.edges);
  } else if (form == "e") {
    if (t.size() != 8 + 2 * bins + 1)
      in.fail("f", concat("listed edges: expected ", 8 + 2 * bins + 1, " values for ", bins,
                          " bins, got ", t.size()));
    p.edges.reserve(bins + 1);
    for (std::size_t i = 0; i <= bins; ++i)
      p.edges.push_back(in.parse<Scalar>("f.edges", t[next++]));
  } else {
    in.fail("f", concat("the edge form '", form, "' is not u (uniform) or e (listed)"));
  }
  p.counts.reserve(bins);
  for (std::size_t i = 0; i < bins; ++i)
    p.counts.push_back(in.parse<Eigen::Index>("f.counts", t[next++]));
  return p;
}

}  // namespace detail
}  // namespace hbos
