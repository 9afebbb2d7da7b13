#include "row_blocks.hpp"

#include <algorithm>
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
  Eigen::Index d = 0;
  CsvHandlers handlers;
  handlers.on_layout = [&](const CsvLayout& layout) {
    d = layout.n_features();
    throw Stop{};
  };
  handlers.on_row = [](const CsvRow&) {};
  try {
    read_csv_rows(path, csv, handlers);
  } catch (const Stop&) {
  }
  return d;
}

void for_each_row_block(const std::string& path, const CsvOptions& csv,
                        const std::function<void(const RowBlock&)>& on_block) {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  if (is_npy_path(path)) {
    const Eigen::MatrixXd x = read_npy(path).values;
    const Eigen::Index step = rows_per_block(x.cols());
    for (Eigen::Index start = 0; start < x.rows(); start += step) {
      const RowMajor block = x.middleRows(start, std::min(step, x.rows() - start));
      on_block(block);
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
  read_csv_rows(path, csv, handlers);
  flush();
}

}  // namespace hbos::cli
