#include "dynbench/cells.hpp"

#include "frontend/camera.hpp"
#include "frontend/residual_screen.hpp"
#include "frontend/rough_pose.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>
#include <hbos/version.hpp>

#include <algorithm>
#include <filesystem>

namespace hbos::dynbench {

void use_full_grid(BenchSettings& settings) {
  settings.scenarios = all_scenarios();
  settings.variants = all_variants();
  settings.seeds = {1, 2, 3};
  settings.frames = 0;
}

const std::vector<std::string>& all_scenarios() {
  static const std::vector<std::string> names = {"walking_xyz",    "walking_static",
                                                 "walking_rpy",    "walking_halfsphere",
                                                 "sitting_static", "sitting_xyz"};
  return names;
}

const std::vector<std::string>& all_variants() {
  static const std::vector<std::string> names = {"perfect",         "eroded",       "dilated",
                                                 "missing",         "delayed",      "boxes",
                                                 "object_unmasked", "person_missed"};
  return names;
}

std::vector<std::string> screens_in_order(const std::vector<std::string>& selected) {
  const std::vector<std::string>& known = slam::screen_strategy_names();
  for (const std::string& s : selected) {
    if (std::find(known.begin(), known.end(), s) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw InvalidArgument(fmt::format("screen '{}' is not one of {}", s, list));
    }
  }
  const auto wanted = [&](const std::string& s) {
    return std::find(known.begin(), known.end(), s) != known.end() &&
           (selected.empty() || std::find(selected.begin(), selected.end(), s) != selected.end());
  };
  std::vector<std::string> order;
  for (const char* s : {"none", "fixed", "chi2", "quantile", "mad", "paper", "default"}) {
    if (wanted(s)) order.emplace_back(s);
  }
  for (const std::string& s : known) {  // a strategy added to the front end later
    if (wanted(s) && std::find(order.begin(), order.end(), s) == order.end()) order.push_back(s);
  }
  return order;
}

std::string Cell::id() const { return fmt::format("{}_s{}_{}_{}", scenario, seed, mask, screen); }

std::vector<Cell> grid_cells(const BenchSettings& settings) {
  const std::vector<std::string> screens = screens_in_order(settings.screens);
  const auto has = [&](const char* s) {
    return std::find(screens.begin(), screens.end(), s) != screens.end();
  };
  std::vector<Cell> cells;
  for (const std::string& scenario : settings.scenarios) {
    for (const std::uint64_t seed : settings.seeds) {
      // Without a mask: no screen at all and hbos's default screen alone, or every screen.
      if (settings.every_screen_unmasked) {
        for (const std::string& s : screens) cells.push_back({scenario, seed, "none", s});
      } else {
        for (const char* s : {"none", "default"}) {
          if (has(s)) cells.push_back({scenario, seed, "none", s});
        }
      }
      for (const std::string& variant : settings.variants) {
        for (const std::string& s : screens) cells.push_back({scenario, seed, variant, s});
      }
    }
  }
  return cells;
}

std::string sequence_dir(const BenchSettings& settings, const std::string& scenario,
                         std::uint64_t seed) {
  const std::string length = settings.frames > 0 ? fmt::format("{}f", settings.frames) : "full";
  // The scenario's own cast keeps the name it always had, so existing caches stay valid.
  const std::string cast = settings.people > 0 ? fmt::format("_{}people", settings.people) : "";
  return (std::filesystem::path(settings.cache_dir) /
          fmt::format("{}_seed{}_{}{}", scenario, seed, length, cast))
      .string();
}

nlohmann::json cell_settings(const BenchSettings& settings, const Cell& cell,
                             const std::string& sequence_fingerprint) {
  const slam::Config& c = settings.base;
  // The intrinsics themselves, not only the camera's name: a camera file edited between two runs
  // must not let the second reuse cells the first computed with other numbers.
  const slam::CameraModel camera = slam::load_camera(settings.camera);
  const nlohmann::json intrinsics = {{"fx", camera.fx}, {"fy", camera.fy},
                                     {"cx", camera.cx}, {"cy", camera.cy},
                                     {"k1", camera.k1}, {"k2", camera.k2},
                                     {"p1", camera.p1}, {"p2", camera.p2},
                                     {"k3", camera.k3}, {"depth_factor", camera.depth_factor}};
  nlohmann::json key = {
      {"format", 1},
      {"scenario", cell.scenario},
      {"seed", cell.seed},
      {"mask", cell.mask},
      {"screen", cell.screen},
      {"frames", settings.frames},
      {"camera", settings.camera},
      {"camera_model", intrinsics},
      {"tracker", slam::to_string(c.tracker)},
      {"rounds", c.screen.rounds},
      {"mask_evidence", c.screen.mask_evidence},
      {"track_history", c.screen.track_history},
      {"provisional_consensus", c.screen.provisional_consensus},
      {"later_rounds_gate_floor", slam::later_rounds_gate_floor(c)},
      {"later_rounds_rigid_field", slam::later_rounds_rigid_field(c)},
      {"leverage_guard", slam::to_json(c.guard)},
      {"history_forgetting", c.map.history.forgetting},
      {"rough_pose", slam::to_string(c.rough_pose.method)},
      {"ransac_threshold_px", c.rough_pose.ransac_threshold_px},
      {"ransac_refit_check", c.rough_pose.check_refit},
      {"jump_limit", slam::to_json(c.jump_limit)},
      {"history_consensus", c.rough_pose.history_consensus},
      {"history_consensus_rule", slam::kHistoryConsensusRule},
      {"orb_features", c.extraction.features},
      {"huber_from_noise", c.refinement.huber_from_noise},
      {"map_max_far_points", c.map.keyframes.max_far_points},
      {"local_bundle_adjustment", c.map.local_bundle.enabled},
      {"hbos_version", fmt::format("{}.{}.{}", kVersionMajor, kVersionMinor, kVersionPatch)},
      {"sequence_fingerprint", sequence_fingerprint}};
  // Only the map tracker relocalises: the frame tracker's cells keep their keys.
  if (c.tracker == slam::TrackerKind::kMap)
    key["relocaliser_refit_check"] = c.map.relocalisation.check_refit;
  // Keyed only when on, so the cells of runs before the option existed stay valid.
  if (c.map.point_noise.enabled) key["point_noise"] = slam::to_json(c.map.point_noise);
  if (c.map.noise_history.enabled) key["noise_history"] = slam::to_json(c.map.noise_history);
  return key;
}

}  // namespace hbos::dynbench
