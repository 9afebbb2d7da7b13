#include "frontend/grid/grid_command.hpp"

#include "common/atomic_file.hpp"
#include "common/stop_on_signal.hpp"
#include "frontend/grid/grid_report.hpp"
#include "frontend/grid/grid_run.hpp"
#include "frontend/slam_command.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <string>

namespace hbos::slam {

int run_variant_grid_command(const Config& config, const CameraModel& camera,
                             const RgbdSequence& sequence, bool quiet, std::ostream& out,
                             std::ostream& err) {
  namespace fs = std::filesystem;
  const examples::StopOnSignal stop_on_signal;
  const std::string tracker = to_string(config.tracker);
  const fs::path dir(config.output.dir);
  GridResult grid;
  try {
    grid = run_variant_grid(config, sequence, camera, (dir / "variant_grid_runs").string(),
                            quiet ? nullptr : &err, examples::StopOnSignal::flag());
  } catch (const fs::filesystem_error& e) {
    err << "hbos-slam: error: " << e.what() << "\n";
    return kSlamOutputError;
  }
  const std::string settings = fmt::format(
      "sequence `{}` ({} frames, camera {}), rough pose {} ({} px), {} screening rounds, "
      "{} of {} runs reused from the cache",
      fs::path(config.dataset.path).filename().string(), grid.frames, camera.name,
      to_string(config.rough_pose.method), config.rough_pose.ransac_threshold_px,
      config.screen.rounds, grid.reused, grid.runs.size());
  const std::string md = grid_markdown(grid, settings);
  out << md;
  try {
    const std::string md_path = (dir / ("variant_grid_" + tracker + ".md")).string();
    const std::string json_path = (dir / ("variant_grid_" + tracker + ".json")).string();
    examples::write_file_atomically(md_path, md);
    examples::write_file_atomically(json_path, grid_json(grid, settings).dump(1) + "\n");
    out << "wrote " << md_path << "\nwrote " << json_path << "\n";
  } catch (const std::runtime_error& e) {
    err << "hbos-slam: error: " << e.what() << "\n";
    return kSlamOutputError;
  }
  if (!grid.complete) {
    err << fmt::format(
        "hbos-slam: interrupted after {} runs; they are kept in {} and reused when the same "
        "command is run again\n",
        grid.runs.size(), (dir / "variant_grid_runs").string());
    return kSlamInterrupted;
  }
  return kSlamOk;
}

}  // namespace hbos::slam
