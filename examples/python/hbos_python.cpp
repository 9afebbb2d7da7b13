// The C++ half of the Python module `hbos` (examples/python/hbos/__init__.py holds the PyOD-style
// HBOS class): the default model and the PyOD mode, fitted and scored on numpy float64 arrays
// read in place (any strides, C or Fortran order: an Eigen::Map over numpy's buffer, no copy),
// with the GIL released while the library runs, and their model files; and the passes of the
// sharded fits (hbos/merge.hpp, hbos/pyod/merge.hpp) that hbos.dask reduces over the chunks of a
// Dask array.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <hbos/merge.hpp>
#include <hbos/model.hpp>
#include <hbos/model_file.hpp>
#include <hbos/pyod/merge.hpp>
#include <hbos/pyod/model.hpp>
#include <hbos/pyod/model_file.hpp>
#include <hbos/threshold.hpp>

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace py = pybind11;

namespace {

using Strided = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
/// A float64 array; forcecast converts other dtypes (a copy, as numpy.asarray would).
using Array = py::array_t<double, py::array::forcecast>;

/// The 2-D array as an Eigen map over its own buffer (a 1-D array is one column). Negative or
/// unaligned strides are refused here; the Python layer copies such arrays first.
Strided as_matrix(const Array& x) {
  if (x.ndim() != 1 && x.ndim() != 2)
    throw std::invalid_argument("X must be a 1-D or 2-D array, got " + std::to_string(x.ndim()) +
                                " dimensions");
  const Eigen::Index rows = x.shape(0);
  const Eigen::Index cols = x.ndim() == 2 ? x.shape(1) : 1;
  const Eigen::Index row_stride = x.strides(0);
  const Eigen::Index col_stride = x.ndim() == 2 ? x.strides(1) : row_stride * rows;
  constexpr Eigen::Index size = sizeof(double);
  if (row_stride <= 0 || col_stride <= 0 || row_stride % size != 0 || col_stride % size != 0)
    throw std::invalid_argument("X has negative or unaligned strides; pass a contiguous copy");
  return Strided(
      x.data(), rows, cols,
      Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(col_stride / size, row_stride / size));
}

/// A view of a 1-D numpy array that the C++ core writes into: scores go straight into the array
/// that Python gets, with no copy.
Eigen::Map<Eigen::VectorXd> as_vector(py::array_t<double>& a) {
  return {a.mutable_data(), static_cast<Eigen::Index>(a.size())};
}

py::array_t<double> to_numpy(const Eigen::VectorXd& v) {
  py::array_t<double> out(v.size());
  std::copy(v.data(), v.data() + v.size(), out.mutable_data());
  return out;
}

/// The default model: `bins` coarse equal-width bins (or a rule name) x `shifts`.
struct DefaultModel {
  explicit DefaultModel(hbos::Hbosd m, py::array_t<double> scores = py::array_t<double>(),
                        std::optional<double> t = std::nullopt, py::object l = py::none())
      : model(std::move(m)),
        training_scores(std::move(scores)),
        threshold(t),
        labels(std::move(l)) {}
  hbos::Hbosd model;
  py::array_t<double> training_scores;  // empty for a loaded or merged model
  // PyOD's threshold_ and labels_ of the training scores, when fitted with a contamination.
  std::optional<double> threshold;
  py::object labels;
};

/// PyOD's labels_, `(scores > threshold).astype(int)`, written once into the array Python gets.
void label_into(const double* scores, Eigen::Index n, double threshold, std::int64_t* labels) {
  for (Eigen::Index i = 0; i < n; ++i) labels[i] = scores[i] > threshold ? 1 : 0;
}

hbos::HbosParams default_params(const std::string& bins, Eigen::Index shifts) {
  hbos::HbosParams params;
  params.feature.binning.shifts = shifts;
  if (bins == "auto") {
    params.feature.binning.rule = hbos::BinCountRule::BirgeRozenblac;
  } else if (!bins.empty()) {
    params.feature.binning.bins = std::stol(bins);
  }
  return params;
}

/// Fits and scores X; with a contamination also PyOD's threshold_ (numpy's percentile, bit for
/// bit, hbos::compute_threshold) and labels_, so that HBOS().fit does no pass over the scores in
/// numpy.
DefaultModel fit_default(const Array& x, const std::string& bins, Eigen::Index shifts,
                         std::optional<double> contamination) {
  const hbos::HbosParams params = default_params(bins, shifts);
  const Strided m = as_matrix(x);
  py::array_t<double> scores = py::array_t<double>(m.rows());
  Eigen::Map<Eigen::VectorXd> out = as_vector(scores);
  std::optional<py::array_t<std::int64_t>> labels;
  if (contamination) labels.emplace(m.rows());
  std::optional<hbos::Hbosd> model;
  std::optional<double> threshold;
  {
    py::gil_scoped_release release;
    model.emplace(hbos::Hbosd::fit_and_score(m, out, params));
    if (contamination) {
      std::vector<double> scratch;
      threshold = hbos::compute_threshold(out, hbos::Contamination{*contamination}, scratch);
      label_into(out.data(), out.size(), *threshold, labels->mutable_data());
    }
  }
  py::object label_array = py::none();
  if (labels) label_array = std::move(*labels);
  return DefaultModel(std::move(*model), std::move(scores), threshold, std::move(label_array));
}

// ---- the sharded fit: a range summary is (lo, hi, rows), a count summary a list of int64 arrays

using Range = std::tuple<py::array_t<double>, py::array_t<double>, Eigen::Index>;
using IndexArray = py::array_t<Eigen::Index, py::array::forcecast>;

hbos::RangeSummary<double> range_from(const Array& lo, const Array& hi, Eigen::Index rows) {
  if (lo.ndim() != 1 || hi.ndim() != 1)
    throw std::invalid_argument("a range summary's lo and hi must be 1-D arrays");
  hbos::RangeSummary<double> r;
  r.lo.assign(lo.data(), lo.data() + lo.size());
  r.hi.assign(hi.data(), hi.data() + hi.size());
  r.rows = rows;
  return r;
}

Range summarize_range(const Array& x) {
  const Strided m = as_matrix(x);
  hbos::RangeSummary<double> r;
  {
    py::gil_scoped_release release;
    r = hbos::summarize_range(m);
  }
  py::array_t<double> lo(static_cast<py::ssize_t>(r.lo.size()));
  py::array_t<double> hi(static_cast<py::ssize_t>(r.hi.size()));
  std::copy(r.lo.begin(), r.lo.end(), lo.mutable_data());
  std::copy(r.hi.begin(), r.hi.end(), hi.mutable_data());
  return {lo, hi, r.rows};
}

/// A plan's integer counts of one shard (the GIL released while counting), a numpy array per
/// feature: the default mode's ShardedFit and the PyOD mode's PyodShardedFit alike.
template <class Plan>
std::vector<py::array_t<Eigen::Index>> counts_of_shard(const Plan& plan, const Strided& m) {
  hbos::CountSummary c;
  {
    py::gil_scoped_release release;
    c = plan.count(m);
  }
  std::vector<py::array_t<Eigen::Index>> out;
  for (const auto& feature : c.counts) {
    py::array_t<Eigen::Index> a(static_cast<py::ssize_t>(feature.size()));
    std::copy(feature.begin(), feature.end(), a.mutable_data());
    out.push_back(std::move(a));
  }
  return out;
}

std::vector<py::array_t<Eigen::Index>> count_shard(const Array& x, const Array& lo, const Array& hi,
                                                   Eigen::Index rows, const std::string& bins,
                                                   Eigen::Index shifts) {
  const hbos::ShardedFit<double> plan(range_from(lo, hi, rows), default_params(bins, shifts));
  return counts_of_shard(plan, as_matrix(x));
}

DefaultModel model_from_counts(const Array& lo, const Array& hi, Eigen::Index rows,
                               const std::string& bins, Eigen::Index shifts,
                               const std::vector<IndexArray>& counts) {
  const hbos::ShardedFit<double> plan(range_from(lo, hi, rows), default_params(bins, shifts));
  hbos::CountSummary total;
  total.rows = rows;
  for (const auto& feature : counts) {
    if (feature.ndim() != 1) throw std::invalid_argument("each feature's counts must be 1-D");
    total.counts.emplace_back(feature.data(), feature.data() + feature.size());
  }
  return DefaultModel(plan.model(total));
}

// ---- the PyOD mode's sharded fit: the same range summary, PyOD's parameters, then the counts

hbos::PyodParams pyod_params(Eigen::Index n_bins, bool auto_bins, double alpha, double tol,
                             double contamination) {
  hbos::PyodParams p;
  p.n_bins = n_bins;
  p.auto_bins = auto_bins;
  p.alpha = alpha;
  p.tol = tol;
  p.contamination = contamination;
  return p;
}

std::vector<py::array_t<Eigen::Index>> pyod_count_shard(const Array& x, const Array& lo,
                                                        const Array& hi, Eigen::Index rows,
                                                        Eigen::Index n_bins, double alpha,
                                                        double tol, double contamination) {
  const hbos::PyodShardedFit<double> plan(range_from(lo, hi, rows),
                                          pyod_params(n_bins, false, alpha, tol, contamination));
  return counts_of_shard(plan, as_matrix(x));
}

/// The PyOD mode's histograms merged from shards (hbos::PyodHistograms), with what rebuilds them
/// (range, parameters, counts: a few numbers per bin), which is how they pickle to workers.
struct PyodMerged {
  hbos::PyodHistograms<double> histograms;
  py::tuple state;
};

PyodMerged pyod_from_counts(const Array& lo, const Array& hi, Eigen::Index rows,
                            Eigen::Index n_bins, double alpha, double tol, double contamination,
                            const std::vector<IndexArray>& counts) {
  const hbos::PyodShardedFit<double> plan(range_from(lo, hi, rows),
                                          pyod_params(n_bins, false, alpha, tol, contamination));
  hbos::CountSummary total;
  total.rows = rows;
  for (const auto& feature : counts) {
    if (feature.ndim() != 1) throw std::invalid_argument("each feature's counts must be 1-D");
    total.counts.emplace_back(feature.data(), feature.data() + feature.size());
  }
  return PyodMerged{plan.histograms(total),
                    py::make_tuple(lo, hi, rows, n_bins, alpha, tol, contamination, counts)};
}

}  // namespace

PYBIND11_MODULE(_hbos, m) {
  m.doc() = "C++ core of the hbos Python module (use hbos.HBOS)";
  py::register_exception<hbos::InvalidArgument>(m, "InvalidArgument", PyExc_ValueError);

  py::class_<DefaultModel>(m, "DefaultModel")
      .def_static("fit", &fit_default, py::arg("X"), py::arg("bins"), py::arg("shifts"),
                  py::arg("contamination") = py::none())
      .def("decision_function",
           [](const DefaultModel& self, const Array& x) {
             const Strided mx = as_matrix(x);
             py::array_t<double> scores = py::array_t<double>(mx.rows());
             Eigen::Map<Eigen::VectorXd> out = as_vector(scores);
             {
               py::gil_scoped_release release;
               self.model.score_into(mx, out);
             }
             return scores;
           })
      .def_property_readonly("training_scores",
                             [](const DefaultModel& self) { return self.training_scores; })
      .def_property_readonly("threshold", [](const DefaultModel& self) { return self.threshold; })
      .def_property_readonly("labels", [](const DefaultModel& self) { return self.labels; })
      .def_property_readonly("n_features",
                             [](const DefaultModel& s) { return s.model.n_features(); })
      .def("save", [](const DefaultModel& self,
                      const std::string& path) { hbos::save_model(self.model, path); })
      .def_static(
          "load",
          [](const std::string& path) { return DefaultModel(hbos::load_hbos<double>(path)); })
      .def_static("from_counts", &model_from_counts, py::arg("lo"), py::arg("hi"), py::arg("rows"),
                  py::arg("bins"), py::arg("shifts"), py::arg("counts"))
      // Pickled as its model-file text (exact: scores come back bit for bit), so a model
      // travels to Dask workers; the training scores stay behind.
      .def(py::pickle([](const DefaultModel& self) { return hbos::to_model_text(self.model); },
                      [](const std::string& text) {
                        return DefaultModel(hbos::hbos_from_model_text<double>(text, "pickle"));
                      }));

  py::class_<hbos::PyodHbosd>(m, "PyodModel")
      .def_static(
          "fit",
          [](const Array& x, Eigen::Index n_bins, bool auto_bins, double alpha, double tol,
             double contamination) {
            const hbos::PyodParams p = pyod_params(n_bins, auto_bins, alpha, tol, contamination);
            const Strided mx = as_matrix(x);
            py::gil_scoped_release release;
            return hbos::PyodHbosd::fit(mx, p);
          },
          py::arg("X"), py::arg("n_bins"), py::arg("auto_bins"), py::arg("alpha"), py::arg("tol"),
          py::arg("contamination"))
      .def("decision_function",
           [](const hbos::PyodHbosd& self, const Array& x) {
             const Strided mx = as_matrix(x);
             Eigen::VectorXd scores;
             {
               py::gil_scoped_release release;
               scores = self.decision_function(mx);
             }
             return to_numpy(scores);
           })
      .def_property_readonly("decision_scores",
                             [](const hbos::PyodHbosd& s) { return to_numpy(s.decision_scores()); })
      .def_property_readonly("threshold", &hbos::PyodHbosd::threshold)
      .def_property_readonly("labels",
                             [](const hbos::PyodHbosd& s) {
                               const Eigen::VectorXi& l = s.labels();
                               py::array_t<std::int64_t> out(l.size());
                               std::copy(l.data(), l.data() + l.size(), out.mutable_data());
                               return out;
                             })
      .def_property_readonly("n_features", &hbos::PyodHbosd::n_features)
      .def("bin_edges",
           [](const hbos::PyodHbosd& s, Eigen::Index j) { return to_numpy(s.bin_edges(j)); })
      .def("densities",
           [](const hbos::PyodHbosd& s, Eigen::Index j) { return to_numpy(s.densities(j)); })
      .def("save", [](const hbos::PyodHbosd& self,
                      const std::string& path) { hbos::save_model(self, path); })
      .def_static("load",
                  [](const std::string& path) { return hbos::load_pyod_hbos<double>(path); });

  py::class_<PyodMerged>(m, "PyodHistograms")
      .def_static("from_counts", &pyod_from_counts, py::arg("lo"), py::arg("hi"), py::arg("rows"),
                  py::arg("n_bins"), py::arg("alpha"), py::arg("tol"), py::arg("contamination"),
                  py::arg("counts"))
      .def("decision_function",
           [](const PyodMerged& self, const Array& x) {
             const Strided mx = as_matrix(x);
             Eigen::VectorXd scores;
             {
               py::gil_scoped_release release;
               scores = self.histograms.decision_function(mx);
             }
             return to_numpy(scores);
           })
      .def("model",
           [](const PyodMerged& self, const Array& training_scores) {
             if (training_scores.ndim() != 1)
               throw std::invalid_argument("the training scores must be a 1-D array");
             const Eigen::Map<const Eigen::VectorXd> s(training_scores.data(),
                                                       training_scores.size());
             return self.histograms.model(s);
           })
      .def_property_readonly("n_features",
                             [](const PyodMerged& s) { return s.histograms.n_features(); })
      .def_property_readonly("rows", [](const PyodMerged& s) { return s.histograms.rows(); })
      .def("bin_edges",
           [](const PyodMerged& s, Eigen::Index j) { return to_numpy(s.histograms.bin_edges(j)); })
      .def("densities",
           [](const PyodMerged& s, Eigen::Index j) { return to_numpy(s.histograms.densities(j)); })
      .def(py::pickle([](const PyodMerged& self) { return self.state; },
                      [](const py::tuple& t) {
                        if (t.size() != 8)
                          throw std::invalid_argument("not a pickled PyodHistograms");
                        return pyod_from_counts(
                            t[0].cast<Array>(), t[1].cast<Array>(), t[2].cast<Eigen::Index>(),
                            t[3].cast<Eigen::Index>(), t[4].cast<double>(), t[5].cast<double>(),
                            t[6].cast<double>(), t[7].cast<std::vector<IndexArray>>());
                      }));

  m.def("summarize_range", &summarize_range, py::arg("X"),
        "pass 1 of the sharded fit: per feature min and max of X, and its row count");
  m.def("count_shard", &count_shard, py::arg("X"), py::arg("lo"), py::arg("hi"), py::arg("rows"),
        py::arg("bins"), py::arg("shifts"),
        "pass 2: per feature the rows of X in each bin of the plan fixed by the global range");
  m.def("pyod_count_shard", &pyod_count_shard, py::arg("X"), py::arg("lo"), py::arg("hi"),
        py::arg("rows"), py::arg("n_bins"), py::arg("alpha"), py::arg("tol"),
        py::arg("contamination"),
        "pass 2 of the PyOD mode's sharded fit: numpy's counts of X in the edges of the global "
        "range");
  m.def(
      "pyod_check_params",
      [](Eigen::Index n_bins, double alpha, double tol, double contamination) {
        hbos::detail::validate(pyod_params(n_bins, false, alpha, tol, contamination));
      },
      py::arg("n_bins"), py::arg("alpha"), py::arg("tol"), py::arg("contamination"),
      "PyOD's parameter checks, before any pass of the sharded fit");
  m.def("model_kind", [](const std::string& path) { return hbos::read_model_info(path).kind; });
}
