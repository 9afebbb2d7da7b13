#pragma once
/// \file
/// Reading NumPy `.npy` files (format versions 1.0, 2.0 and 3.0; numpy.lib.format) holding a 1-D or
/// 2-D array of little-endian float64 (`<f8`) or float32 (`<f4`), in C or Fortran order: what
/// `numpy.save(path, X)` writes for a float array. The header is parsed here (no numpy needed);
/// anything else (big-endian, integers, objects, 3-D, a truncated file) is refused with the file
/// and the reason.
///
/// `read_data` is the input of `hbos-score fit` and `hbos-score score` when they hold the data: a
/// `.npy` path is read by read_npy, anything else as CSV by the streaming CSV reader
/// (csv_reader.hpp), in both cases straight into the one buffer kept (data_matrix.hpp).

#include <Eigen/Core>
#include <stdexcept>
#include <string>

#include "csv_reader.hpp"
#include "data_matrix.hpp"

namespace hbos::cli {

/// A malformed or unsupported .npy file; `what()` reads `path: message`.
class NpyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An array read from a .npy file, as doubles (float32 values are widened exactly).
struct NpyArray {
  /// rows x cols in the file's order: row-major for C order, column-major for Fortran order
  /// (a 1-D array is one column)
  DataMatrix values;
  bool float32 = false;  ///< the file held float32 values
};

/// Reads the .npy file at `path` into its final buffer (float64 data is read in place; float32
/// widened 1 MiB at a time). \throws NpyError naming the file and what is wrong.
[[nodiscard]] NpyArray read_npy(const std::string& path);

/// Whether `path` names a `.npy` file: its suffix in any case, or numpy's magic string at the
/// start of a regular file. How read_data decides.
[[nodiscard]] bool is_npy_path(const std::string& path);

/// Refuses the CSV-only options for the .npy file `path` (a label or ignored column, a header
/// mode, a delimiter): a .npy array is all features, and an option that would be dropped without
/// a word would fit or score other data than the user asked for. \throws NpyError naming the
/// file and the option.
void refuse_csv_options(const std::string& path, const CsvOptions& csv);

/// The rows of a .npy file as the one-shot scorer holds them: row-major, in one buffer (a
/// Fortran-order file is transposed into a second buffer, then the first is freed).
/// \throws NpyError as read_npy, or for a CSV-only option (refuse_csv_options).
[[nodiscard]] RowStore read_npy_rows(const std::string& path, const CsvOptions& csv);

/// The feature matrix of `path`, held once: read_npy for a `.npy` file, else CSV read with `csv`
/// row by row into a row-major store (features only: a label column or ignored columns are
/// dropped; the column names are not kept). \throws NpyError or CsvError.
[[nodiscard]] DataMatrix read_data(const std::string& path, const CsvOptions& csv);

}  // namespace hbos::cli
