// libFuzzer target: the model-file loaders (hbos/model_file.hpp, hbos/pyod/model_file.hpp) on
// fuzzed text, both model kinds and both scalar types (the first byte chooses). Documented
// outcomes: a model, or hbos::InvalidArgument naming the line and the field. A model that loads
// must also score finite, non-negative values (the default kind; the PyOD kind finite ones), and
// its text written again must load to the same text (the format round-trips).

#include <hbos/model_file.hpp>
#include <hbos/pyod/model_file.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"

namespace {

/// Rows to score: values around, at and far beyond any fitted range.
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> probe(Eigen::Index features) {
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> x(5, features);
  for (Eigen::Index j = 0; j < features; ++j) {
    x(0, j) = Scalar(0);
    x(1, j) = Scalar(1);
    x(2, j) = Scalar(-3.5);
    x(3, j) = Scalar(1e6);
    x(4, j) = -std::numeric_limits<Scalar>::max();
  }
  return x;
}

template <class Scalar>
void default_kind(std::string_view text) {
  const auto model = hbos::hbos_from_model_text<Scalar>(text, "fuzz");
  if (model.n_features() <= 4096) {
    const auto scores = model.score(probe<Scalar>(model.n_features()));
    for (Eigen::Index i = 0; i < scores.size(); ++i)
      check(std::isfinite(scores(i)) && scores(i) >= Scalar(0));
  }
  const std::string again = hbos::to_model_text(model);
  check(hbos::to_model_text(hbos::hbos_from_model_text<Scalar>(again, "again")) == again);
}

template <class Scalar>
void pyod_kind(std::string_view text) {
  const auto model = hbos::pyod_hbos_from_model_text<Scalar>(text, "fuzz");
  if (model.n_features() <= 4096) {
    const auto scores = model.decision_function(probe<Scalar>(model.n_features()));
    for (Eigen::Index i = 0; i < scores.size(); ++i) check(std::isfinite(scores(i)));
  }
  const std::string again = hbos::to_model_text(model);
  check(hbos::to_model_text(hbos::pyod_hbos_from_model_text<Scalar>(again, "again")) == again);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    switch (data[0] % 4) {
      case 0:
        default_kind<double>(text);
        break;
      case 1:
        default_kind<float>(text);
        break;
      case 2:
        pyod_kind<double>(text);
        break;
      default:
        pyod_kind<float>(text);
        break;
    }
  } catch (const hbos::InvalidArgument&) {
  }
  return 0;
}
