#pragma once
/// \file
/// The values of a CSV file as hbos-score keeps them: one contiguous row-major buffer of doubles
/// that grows row by row without ever holding two copies.

#include <Eigen/Core>
#include <cstddef>
#include <cstdlib>
#include <memory>

namespace hbos::cli {

/// A rows x cols row-major matrix of doubles that grows one row at a time.
///
/// Growth uses std::realloc by half the size again each time: glibc serves blocks this large
/// with mmap and grows them with mremap, which moves pages instead of copying them, so the peak
/// memory is the data itself plus unused address space (never resident), not the 2-3x of a
/// std::vector that copies into a doubled buffer. Costs 8 bytes per value and nothing per row.
class RowStore {
 public:
  explicit RowStore(Eigen::Index cols = 0) : cols_(cols) {}

  /// Appends one row of cols() values. \throws std::bad_alloc when memory runs out.
  void append(const double* row);

  /// Sets the row count to `rows` with room for exactly rows x cols() values (for a size known
  /// beforehand, e.g. a .npy header's); rows beyond the old count are left uninitialised for the
  /// caller to fill. \throws std::bad_alloc when memory runs out.
  void resize_rows(Eigen::Index rows);

  [[nodiscard]] Eigen::Index rows() const { return rows_; }
  [[nodiscard]] Eigen::Index cols() const { return cols_; }
  [[nodiscard]] double* data() { return data_.get(); }
  [[nodiscard]] const double* data() const { return data_.get(); }
  [[nodiscard]] double& operator()(Eigen::Index i, Eigen::Index j) { return data_[index(i, j)]; }
  [[nodiscard]] double operator()(Eigen::Index i, Eigen::Index j) const {
    return data_[index(i, j)];
  }
  /// The whole store as an Eigen row-major matrix (no copy).
  [[nodiscard]] auto matrix() const {
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    return Eigen::Map<const RowMajor>(data_.get(), rows_, cols_);
  }
  [[nodiscard]] auto matrix() {
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    return Eigen::Map<RowMajor>(data_.get(), rows_, cols_);
  }

 private:
  struct Free {
    void operator()(double* p) const { std::free(p); }
  };
  [[nodiscard]] std::size_t index(Eigen::Index i, Eigen::Index j) const {
    return static_cast<std::size_t>(i) * static_cast<std::size_t>(cols_) +
           static_cast<std::size_t>(j);
  }

  std::unique_ptr<double[], Free> data_;
  Eigen::Index rows_ = 0;
  Eigen::Index cols_ = 0;
  std::size_t capacity_ = 0;  // in values
};

}  // namespace hbos::cli
