#pragma once
/// \file
/// `hbos-slam --variant-grid`: runs the grid (grid_run.hpp), writes its tables (grid_report.hpp)
/// as `variant_grid_<tracker>.md` and `.json` into the output folder, each atomically.

#include "frontend/camera.hpp"
#include "frontend/config.hpp"
#include "frontend/dataset.hpp"

#include <iosfwd>

namespace hbos::slam {

/// Returns a SlamExitCode (slam_command.hpp): 0, 1 when a file cannot be written, 130 when
/// interrupted (the finished runs stay cached and the tables written so far are marked
/// incomplete).
int run_variant_grid_command(const Config& config, const CameraModel& camera,
                             const RgbdSequence& sequence, bool quiet, std::ostream& out,
                             std::ostream& err);

}  // namespace hbos::slam
