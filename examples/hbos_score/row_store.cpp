#include "row_store.hpp"

#include <algorithm>
#include <cstring>
#include <new>

namespace hbos::cli {

void RowStore::append(const double* row) {
  const auto cols = static_cast<std::size_t>(cols_);
  const std::size_t needed = (static_cast<std::size_t>(rows_) + 1) * cols;
  if (needed > capacity_) {
    // At least 64 KiB, then half as much again: few reallocations, little unused address space.
    const std::size_t grown = std::max({needed, capacity_ + capacity_ / 2, std::size_t{8192}});
    if (grown > static_cast<std::size_t>(-1) / sizeof(double)) throw std::bad_alloc();
    void* bigger = std::realloc(data_.get(), grown * sizeof(double));
    if (bigger == nullptr) throw std::bad_alloc();
    static_cast<void>(data_.release());
    data_.reset(static_cast<double*>(bigger));
    capacity_ = grown;
  }
  if (cols > 0) std::memcpy(data_.get() + needed - cols, row, cols * sizeof(double));
  ++rows_;
}

void RowStore::resize_rows(Eigen::Index rows) {
  const auto count = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols_);
  if (count > static_cast<std::size_t>(-1) / sizeof(double)) throw std::bad_alloc();
  if (count != capacity_) {
    void* resized = std::realloc(data_.get(), std::max<std::size_t>(count, 1) * sizeof(double));
    if (resized == nullptr) throw std::bad_alloc();
    static_cast<void>(data_.release());
    data_.reset(static_cast<double*>(resized));
    capacity_ = std::max<std::size_t>(count, 1);
  }
  rows_ = rows;
}

}  // namespace hbos::cli
