#include "row_blocks.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "npy_reader.hpp"

namespace hbos::cli {

Eigen::Index rows_per_block(Eigen::Index features) {
  constexpr Eigen::Index kMaxRows = 65536;
  constexpr Eigen::Index kMaxValues = Eigen::Index{1} << 20;  // 8 MiB of doubles
  return std::clamp<Eigen::Index>(kMaxValues / std::max<Eigen::Index>(features, 1), 1, kMaxRows);
}

Eigen::Index csv_feature_count(const std::string& path, const CsvOptions& csv) {
  struct Stop {};  // thrown once the layout is known: the rest of the file is not read
  CsvOptions options = csv;
  options.default_names = false;  // the count is all that is needed
  Eigen::Index d = 0;
  CsvHandlers handlers;
  handlers.on_layout = [&](const CsvLayout& layout) {
    d = layout.n_features();
    throw Stop{};
  };
  handlers.on_row = [](const CsvRow&) {};
  try {
    read_csv_rows(path, options, handlers);
  } catch (const Stop&) {
  }
  return d;
}

void for_each_row_block(const std::string& path, const CsvOptions& csv,
                        const std::function<void(const RowBlock&)>& on_block) {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  if (is_npy_path(path)) {
    refuse_csv_options(path, csv);
    // Held once, in the file's order: a C-order file's blocks are handed over in place, a
    // Fortran-order file's copied a block at a time.
    const DataMatrix x = std::move(read_npy(path).values);
    const Eigen::Index step = rows_per_block(x.cols());
    for (Eigen::Index start = 0; start < x.rows(); start += step) {
      const Eigen::Index m = std::min(step, x.rows() - start);
      if (x.column_major()) {
        const RowMajor block = x.matrix().middleRows(start, m);
        on_block(block);
      } else {
        on_block(Eigen::Map<const RowMajor>(x.data() + start * x.cols(), m, x.cols()));
      }
    }
    return;
  }
  std::vector<double> buffer;
  Eigen::Index d = 0, capacity = 0, filled = 0;
  auto flush = [&] {
    if (filled == 0) return;
    on_block(Eigen::Map<const RowMajor>(buffer.data(), filled, d));
    filled = 0;
  };
  CsvHandlers handlers;
  handlers.on_layout = [&](const CsvLayout& layout) {
    d = layout.n_features();
    capacity = rows_per_block(d);
    buffer.resize(static_cast<std::size_t>(capacity * d));
  };
  handlers.on_row = [&](const CsvRow& row) {
    std::copy(row.features, row.features + d, buffer.begin() + filled * d);
    if (++filled == capacity) flush();
  };
  CsvOptions options = csv;
  options.default_names = false;  // blocks of values: no names needed
  read_csv_rows(path, options, handlers);
  flush();
}

}  // namespace hbos::cli
