#pragma once
/// \file
/// Reading NumPy `.npy` files (format versions 1.0, 2.0 and 3.0; numpy.lib.format) holding a 1-D or
/// 2-D array of little-endian float64 (`<f8`) or float32 (`<f4`), in C or Fortran order: what
/// `numpy.save(path, X)` writes for a float array. The header is parsed here (no numpy needed);
/// anything else (big-endian, integers, objects, 3-D, a truncated file) is refused with the file
/// and the reason.
///
/// `read_data_matrix` is the input of `hbos-score fit` and `hbos-score score`: a `.npy` path is
/// read by read_npy, anything else as CSV by the streaming CSV reader (csv_reader.hpp).

#include <Eigen/Core>
#include <stdexcept>
#include <string>

#include "csv_reader.hpp"

namespace hbos::cli {

/// A malformed or unsupported .npy file; `what()` reads `path: message`.
class NpyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An array read from a .npy file, as doubles (float32 values are widened exactly).
struct NpyArray {
  Eigen::MatrixXd values;  ///< rows x cols, column-major (a 1-D array is one column)
  bool float32 = false;    ///< the file held float32 values
};

/// Reads the .npy file at `path`. \throws NpyError naming the file and what is wrong.
[[nodiscard]] NpyArray read_npy(const std::string& path);

/// Whether `path` names a `.npy` file (by its suffix): how read_data_matrix decides.
[[nodiscard]] bool is_npy_path(const std::string& path);

/// The feature matrix of `path`: read_npy for a `.npy` file, else CSV read with `csv` (features
/// only: a label column or ignored columns are dropped). \throws NpyError or CsvError.
[[nodiscard]] Eigen::MatrixXd read_data_matrix(const std::string& path, const CsvOptions& csv);

}  // namespace hbos::cli
