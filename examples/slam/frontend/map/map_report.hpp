#pragma once
/// \file
/// What a map-tracker run writes beyond the shared outputs: `map.json` (share of frames tracked,
/// Table III stage times, map statistics) and `map_frames.csv` (per frame: how it was tracked,
/// stage times, the map's size).

#include "frontend/map/map_run.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hbos::slam {

[[nodiscard]] nlohmann::json map_report_json(const MapRun& run);
[[nodiscard]] std::string map_frames_csv(const MapRun& run);

/// The lines hbos-slam prints after its summary: frames tracked, Table III, the map.
[[nodiscard]] std::string map_summary_text(const MapRun& run);

/// Writes map.json and map_frames.csv into `dir` (atomically) and returns their paths. Throws
/// std::runtime_error when a file cannot be written.
std::vector<std::string> write_map_outputs(const std::string& dir, const MapRun& run);

}  // namespace hbos::slam
