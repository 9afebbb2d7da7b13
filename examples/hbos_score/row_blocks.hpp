#pragma once
/// \file
/// The rows of a data file in blocks of bounded size: how `hbos-score fit` and `hbos-score score`
/// read files of any length in bounded memory (a CSV file is streamed; a `.npy` file is read
/// whole, 8 bytes per value, and handed over block by block).

#include <Eigen/Core>
#include <functional>
#include <string>

#include "csv_reader.hpp"

namespace hbos::cli {

/// A block of feature rows (rows = samples), row-major as the CSV reader fills it.
using RowBlock =
    Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;

/// Rows per block for `features` columns: up to 65536 rows and about 8 MiB of values, at least
/// one row (a file of ten million columns goes one row at a time).
[[nodiscard]] Eigen::Index rows_per_block(Eigen::Index features);

/// Calls `on_block` for consecutive blocks of the feature rows of `path` (`.npy` as read_npy,
/// anything else CSV with `csv`; `-` = standard input), in file order, every row exactly once.
/// \throws CsvError or NpyError on malformed input (the rows before it have been delivered),
///         or whatever `on_block` throws.
void for_each_row_block(const std::string& path, const CsvOptions& csv,
                        const std::function<void(const RowBlock&)>& on_block);

/// The feature count of the CSV file `path` (its first line, read alone). \throws as read_csv.
[[nodiscard]] Eigen::Index csv_feature_count(const std::string& path, const CsvOptions& csv);

}  // namespace hbos::cli
