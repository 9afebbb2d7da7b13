#include "data_matrix.hpp"

namespace hbos::cli {

const double* DataMatrix::column(Eigen::Index j, std::vector<double>& scratch) const {
  const double* first = data() + j * col_stride();
  const Eigen::Index stride = row_stride();
  if (stride == 1 || rows() == 1) return first;
  const Eigen::Index n = rows();
  scratch.resize(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) scratch[static_cast<std::size_t>(i)] = first[i * stride];
  return scratch.data();
}

}  // namespace hbos::cli
