#pragma once
/// \file
/// The values of a data file held once, in the order the file stores them: what `hbos-score fit`
/// and `hbos-score score` keep of the data they read whole. A CSV file and a C-order `.npy` file
/// are row-major, a Fortran-order `.npy` file column-major; nothing is copied into the other
/// order (for 2 x 1e7 values that copy was a second 160 MB).

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "row_store.hpp"

namespace hbos::cli {

/// A rows x cols matrix of doubles in one buffer, row-major or column-major.
class DataMatrix {
 public:
  /// Strides of an Eigen::Map over the buffer (in values): outer = between columns.
  using Stride = Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>;
  using View = Eigen::Map<const Eigen::MatrixXd, 0, Stride>;

  DataMatrix() = default;
  /// Takes `values` as the matrix (rows x cols, row-major) or, when `column_major`, as its
  /// transpose (the cols x rows row-major store of a column-major matrix).
  DataMatrix(RowStore values, bool column_major)
      : values_(std::move(values)), column_major_(column_major) {}

  [[nodiscard]] Eigen::Index rows() const {
    return column_major_ ? values_.cols() : values_.rows();
  }
  [[nodiscard]] Eigen::Index cols() const {
    return column_major_ ? values_.rows() : values_.cols();
  }
  [[nodiscard]] bool column_major() const { return column_major_; }
  /// Value (i, j) is at data()[i * row_stride() + j * col_stride()].
  [[nodiscard]] const double* data() const { return values_.data(); }
  [[nodiscard]] Eigen::Index row_stride() const { return column_major_ ? 1 : cols(); }
  [[nodiscard]] Eigen::Index col_stride() const { return column_major_ ? rows() : 1; }

  /// The whole matrix as an Eigen expression with direct access (no copy).
  [[nodiscard]] View matrix() const {
    return View(data(), rows(), cols(), Stride(col_stride(), row_stride()));
  }

  /// Column j as rows() contiguous values: in place when they are (column-major, or one column),
  /// otherwise gathered into `scratch`. Valid until `scratch` or the matrix changes.
  [[nodiscard]] const double* column(Eigen::Index j, std::vector<double>& scratch) const;

  /// The buffer, handed over (row-major rows x cols, or cols x rows when column_major()); the
  /// matrix is empty afterwards.
  [[nodiscard]] RowStore release() && { return std::move(values_); }

 private:
  RowStore values_;
  bool column_major_ = false;
};

}  // namespace hbos::cli
