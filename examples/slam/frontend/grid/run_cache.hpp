#pragma once
/// \file
/// One finished grid run as JSON: written atomically to the grid's cache folder, read back when
/// the grid is resumed, and embedded in the grid's result file.

#include "frontend/grid/grid_run.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace hbos::slam {

[[nodiscard]] nlohmann::json to_json(const GridRun& run);

/// The cached run in `path` when it exists, parses and was made with `settings`; else nullopt.
[[nodiscard]] std::optional<GridRun> read_cached_run(const std::string& path,
                                                     const std::string& settings);

/// Writes `run` with `settings` to `path` atomically.
void write_cached_run(const std::string& path, const GridRun& run, const std::string& settings);

}  // namespace hbos::slam
