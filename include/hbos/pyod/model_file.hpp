#pragma once
/// \file
/// The PyOD mode's models as files: `save_model(pyod_model, path)` and
/// `load_pyod_hbos<Scalar>(path)`, in the model-file format of hbos/model_file.hpp (same magic
/// line and version, `kind pyod`; grammar in docs/data_science.md).
///
/// Stored: PyOD's parameters (n_bins or `auto`, alpha, tol, contamination), per feature the
/// B_j + 1 edges and B_j counts (PyOD's `bin_edges_`, numpy.histogram's counts), the threshold
/// and the n training scores (`decision_scores_`, one per line, so a loaded model has every
/// attribute PyOD's has). Densities, look-up tables and labels are re-derived on load by the
/// code `fit` uses, and the edges, counts and threshold are checked against what they imply, so
/// a loaded model scores bit for bit like the saved one and a damaged file is refused, naming
/// the file, line and field. Saving is atomic.

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "hbos/detail/text_format.hpp"
#include "hbos/error.hpp"
#include "hbos/model_file.hpp"
#include "hbos/pyod/model.hpp"

namespace hbos {

/// The PyOD-mode model as model-file text (see the file comment).
template <class Scalar>
[[nodiscard]] std::string to_model_text(const PyodHbos<Scalar>& model) {
  detail::TextWriter out;
  detail::write_model_header(out, "pyod", detail::scalar_name<Scalar>(), 1);
  const PyodParams& p = model.params();
  out.line("n_features", model.n_features());
  out.line("n_samples", model.n_samples());
  if (p.auto_bins) {
    out.line("n_bins", "auto");
  } else {
    out.line("n_bins", p.n_bins);
  }
  out.line("alpha", p.alpha);
  out.line("tol", p.tol);
  out.line("contamination", p.contamination);
  out.line("threshold", model.threshold());
  for (Eigen::Index j = 0; j < model.n_features(); ++j) {
    out.line("feature", j);
    const Eigen::VectorXd& e = model.bin_edges(j);
    out.array("edges", std::vector<double>(e.data(), e.data() + e.size()));
    const auto& c = model.counts(j);
    out.array("counts", std::vector<Eigen::Index>(c.data(), c.data() + c.size()));
    out.line("end");
  }
  out.line("decision_scores", model.n_samples());
  const auto& scores = model.decision_scores();
  for (Eigen::Index i = 0; i < scores.size(); ++i) out.bare(scores[i]);
  out.line("end");
  return out.text();
}

/// Parses PyOD-mode model-file text; `source` names it in errors.
/// \throws InvalidArgument naming the source, line and field of the first problem.
template <class Scalar>
[[nodiscard]] PyodHbos<Scalar> pyod_hbos_from_model_text(std::string_view text,
                                                         const std::string& source = "model text") {
  detail::TextReader in(text, source);
  const ModelFileInfo info = detail::expect_model_header<Scalar>(in, "pyod", "load_pyod_hbos");
  // Version 2 changed the default model's layout only: PyOD-mode files stay version 1.
  if (info.version != 1)
    in.fail("hbos-model-file",
            detail::concat("a PyOD-mode model file is version 1, not ", info.version));
  const auto d = in.value<Eigen::Index>("n_features");
  if (d < 1 || d > (Eigen::Index{1} << 24))
    in.fail("n_features", detail::concat("must lie in [1, 2^24], got ", d));
  const auto n = in.value<Eigen::Index>("n_samples");
  if (n < 1 || static_cast<std::size_t>(n) > detail::kMaxModelArray)
    in.fail("n_samples", detail::concat("must lie in [1, 2^31], got ", n));
  // Each parameter is checked as soon as it is read (the others still hold valid defaults), so
  // an error names its own line.
  PyodParams params;
  auto check = [&](std::string_view key) {
    try {
      detail::validate(params);
    } catch (const InvalidArgument& e) {
      in.fail(key, detail::message_of(e));
    }
  };
  const std::string_view bins = in.expect("n_bins", 1)[0];
  params.auto_bins = bins == "auto";
  if (!params.auto_bins) params.n_bins = in.parse<Eigen::Index>("n_bins", bins);
  check("n_bins");
  params.alpha = in.value<double>("alpha");
  check("alpha");
  params.tol = in.value<double>("tol");
  check("tol");
  params.contamination = in.value<double>("contamination");
  check("contamination");
  const auto threshold = in.value<Scalar>("threshold");
  const std::size_t threshold_line = in.line_number();
  std::vector<Eigen::VectorXd> edges;
  std::vector<typename PyodHbos<Scalar>::Counts> counts;
  for (Eigen::Index j = 0; j < d; ++j) {
    const auto index = in.value<Eigen::Index>("feature");
    if (index != j) in.fail("feature", detail::concat("expected feature ", j, ", got ", index));
    const auto e = in.array<double>("edges", detail::kMaxModelArray);
    const auto c = in.array<Eigen::Index>("counts", detail::kMaxModelArray);
    if (e.size() != c.size() + 1)
      in.fail("counts", detail::concat(c.size(), " counts for ", e.size(), " edges (needs ",
                                       e.size() - 1, ")"));
    edges.emplace_back(
        Eigen::Map<const Eigen::VectorXd>(e.data(), static_cast<Eigen::Index>(e.size())));
    counts.emplace_back(Eigen::Map<const typename PyodHbos<Scalar>::Counts>(
        c.data(), static_cast<Eigen::Index>(c.size())));
    in.expect("end", 0);
  }
  const auto declared = in.value<Eigen::Index>("decision_scores");
  if (declared != n)
    in.fail("decision_scores", detail::concat(declared, " scores for n_samples = ", n));
  typename PyodHbos<Scalar>::Vector scores(n);
  for (Eigen::Index i = 0; i < n; ++i) scores[i] = in.bare<Scalar>("decision_scores");
  in.expect("end", 0);
  in.expect_end();
  PyodHbos<Scalar> model = [&] {
    try {
      return PyodHbos<Scalar>::from_parts(edges, counts, params, std::move(scores));
    } catch (const InvalidArgument& e) {
      throw InvalidArgument(detail::concat(source, ": ", detail::message_of(e)));
    }
  }();
  if (!(model.threshold() == threshold))
    throw InvalidArgument(detail::concat(source, ", line ", threshold_line, " (threshold): ",
                                         threshold, " is not the (1 - contamination) percentile ",
                                         model.threshold(), " of the training scores"));
  return model;
}

/// Writes the PyOD-mode `model` to `path` atomically.
/// \throws InvalidArgument naming the path when it cannot be written.
template <class Scalar>
void save_model(const PyodHbos<Scalar>& model, const std::string& path) {
  detail::write_file_atomically(path, to_model_text(model));
}

/// Loads a PyOD-mode model saved by save_model; it scores bit for bit like the saved one and has
/// the same decision_scores(), threshold() and labels().
/// \throws InvalidArgument naming the file, line and field of a damaged file.
template <class Scalar>
[[nodiscard]] PyodHbos<Scalar> load_pyod_hbos(const std::string& path) {
  return pyod_hbos_from_model_text<Scalar>(detail::read_text_file(path),
                                           detail::concat("model file '", path, "'"));
}

}  // namespace hbos
