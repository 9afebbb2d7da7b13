#include "frontend/run_outputs.hpp"

#include "common/atomic_file.hpp"
#include "eval/plot.hpp"
#include "eval/report.hpp"
#include "eval/trajectory_io.hpp"
#include "frontend/figures.hpp"

#include <fmt/format.h>
#include <hbos/version.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace hbos::slam {

namespace {

// NaN and infinity are not JSON numbers: they become null.
nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json statistics_json(const ErrorStatistics& s, double scale) {
  return {{"rmse", s.rmse * scale},   {"mean", s.mean * scale}, {"median", s.median * scale},
          {"std", s.std_dev * scale}, {"min", s.min * scale},   {"max", s.max * scale},
          {"count", s.count}};
}

}  // namespace

const char* scenario_name(const ScenarioConfig& scenario) {
  return scenario.add_person ? "person" : "static";
}

std::string stats_csv(const std::vector<FrameStats>& stats) {
  std::string csv =
      "frame,stamp,features,matches,person_matches,survivors,person_survivors,static_dropped,"
      "rough_pose,ransac_inliers,tracked,threshold,screen_us,refine_us,mask_us,guard_ratio,"
      "guard_disagreement,guard_shift,guard_bias,guard_dropped\n";
  for (const FrameStats& s : stats) {
    csv += fmt::format(
        "{},{:.6f},{},{},{},{},{},{},{},{},{},{},{:.1f},{:.1f},{:.1f},{},{},{},{},{}\n", s.index,
        s.stamp, s.features, s.matches, s.person_matches, s.survivors, s.person_survivors,
        s.static_dropped,
        !s.rough_from_ransac              ? "constant-velocity"
        : s.rough_from_remembered_statics ? "ransac-remembered-statics"
                                          : "ransac",
        s.ransac_inliers, s.tracked ? 1 : 0,
        std::isfinite(s.threshold) ? fmt::format("{:.6g}", s.threshold) : "", s.screen_us,
        s.refine_us, s.mask_us,
        std::isfinite(s.guard_ratio) ? fmt::format("{:.4g}", s.guard_ratio) : "",
        std::isfinite(s.guard_disagreement) ? fmt::format("{:.4g}", s.guard_disagreement) : "",
        std::isfinite(s.guard_shift) ? fmt::format("{:.4g}", s.guard_shift) : "",
        std::isfinite(s.guard_bias) ? fmt::format("{:.4g}", s.guard_bias) : "", s.guard_dropped);
  }
  return csv;
}

nlohmann::json summary_json(const RunResult& run, const Config& config,
                            const std::string& camera_name) {
  const RunTotals& t = run.totals;
  nlohmann::json j;
  j["tool"] = "hbos-slam";
  j["hbos_version"] = fmt::format("{}.{}.{}", kVersionMajor, kVersionMinor, kVersionPatch);
  j["settings"] = {
      {"dataset", config.dataset.path},
      {"camera", camera_name},
      {"scenario", scenario_name(config.scenario)},
      {"mask", to_string(config.mask.source)},
      {"screen", config.screen.name},
      {"screen_rounds", config.screen.rounds},
      {"huber_from_noise", config.refinement.huber_from_noise},
      {"huber_width", config.refinement.huber_delta},
      {"local_bundle_adjustment", config.map.local_bundle.enabled},
      {"point_noise", to_json(config.map.point_noise)},
      {"noise_history", to_json(config.map.noise_history)},
      {"screen_mask_evidence", config.screen.mask_evidence},
      {"screen_track_history", config.screen.track_history},
      {"screen_provisional_consensus", config.screen.provisional_consensus},
      {"screen_later_rounds_gate_floor", later_rounds_gate_floor(config)},
      {"screen_later_rounds_field", later_rounds_rigid_field(config) ? "rigid" : "affine"},
      {"leverage_guard", to_json(config.guard)},
      {"history_forgetting", config.map.history.forgetting},
      {"rough_pose", to_string(config.rough_pose.method)},
      {"ransac_threshold_px", config.rough_pose.ransac_threshold_px},
      {"ransac_refit_check", config.rough_pose.check_refit},
      {"relocaliser_refit_check", config.map.relocalisation.check_refit},
      {"jump_limit", to_json(config.jump_limit)},
      {"orb_features", config.extraction.features},
      {"orb_spread_cell_px", config.extraction.spread_cell_px},
      {"orb_spread_pool", config.extraction.spread_pool},
      {"person_depth_m", config.scenario.depth_m},
      {"person_speed_px_per_frame", config.scenario.speed_px_per_frame}};
  j["frames"] = t.frames;
  j["frames_tracked"] = t.frames_tracked;
  j["frames_guarded"] = t.frames_guarded;
  j["guard_dropped"] = t.guard_dropped;
  j["frames_rough_pose_ransac"] = t.frames_rough_ransac;
  j["matches"] = t.matches;
  j["person_matches"] = t.person_matches;
  j["person_survivors"] = t.person_survivors;
  j["person_match_survival_share"] =
      t.person_survival_share ? nlohmann::json(*t.person_survival_share) : nlohmann::json(nullptr);
  j["static_matches"] = t.static_matches;
  j["static_dropped"] = t.static_dropped;
  j["static_match_loss_share"] = t.static_loss_share;
  j["mean_screen_us"] = t.mean_screen_us;
  j["mean_refine_us"] = t.mean_refine_us;
  j["mean_mask_us"] = t.mean_mask_us;
  j["median_screen_us"] = t.median_screen_us;
  j["median_mask_us"] = t.median_mask_us;
  if (run.evaluation) {
    const Evaluation& e = *run.evaluation;
    j["ate_m"] = statistics_json(e.ate.stats, 1.0);
    if (e.rpe) {
      j["rpe_trans_mm_per_frame"] = statistics_json(e.rpe->trans_m, 1000.0);
      j["rpe_rot_deg_per_frame"] = statistics_json(e.rpe->rot_deg, 1.0);
    }
    j["evaluation"] = to_json(e);
  } else {
    j["ate_m"] = nullptr;
  }
  if (run.figure) {
    j["figure_frame"] = run.figure->frame.index;
    j["figure_threshold"] = number_or_null(run.figure->result.screen.threshold);
  }
  return j;
}

std::vector<std::string> write_run_outputs(const std::string& dir, const RunResult& run,
                                           const Config& config, const std::string& camera_name,
                                           const Trajectory* groundtruth) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) throw std::runtime_error("cannot create '" + dir + "': " + error.message());
  std::vector<std::string> written;
  const auto path = [&](const char* name) { return (fs::path(dir) / name).string(); };

  const Trajectory estimate = estimate_of(run, "hbos-slam");
  write_tum_trajectory(path("trajectory.txt"), estimate);
  written.push_back(path("trajectory.txt"));
  examples::write_file_atomically(path("stats.csv"), stats_csv(run.stats));
  written.push_back(path("stats.csv"));
  examples::write_file_atomically(path("summary.json"),
                                  summary_json(run, config, camera_name).dump(1) + "\n");
  written.push_back(path("summary.json"));

  if (run.figure) {
    // Says what was done to the frames rather than the scenario's name: "static" means that no
    // person was composited in, and a rendered sequence (or one with masks from files) has
    // people of its own.
    const std::string what =
        fmt::format("frame {} | {}, mask {}, screen {}", run.figure->frame.index,
                    config.scenario.add_person ? "person composited in" : "no person composited in",
                    to_string(config.mask.source), config.screen.name);
    write_png(path("matches.png"), draw_match_figure(*run.figure, what));
    written.push_back(path("matches.png"));
    if (!run.figure->result.screen.magnitude.empty()) {
      write_png(path("residual_histogram.png"), draw_residual_histogram(*run.figure, what));
      written.push_back(path("residual_histogram.png"));
    }
  }
  if (groundtruth != nullptr && run.evaluation) {
    for (const std::string& p : write_plots(dir, *groundtruth, estimate, *run.evaluation)) {
      written.push_back(p);
    }
  }
  return written;
}

std::vector<std::string> remove_stale_outputs(const std::string& dir,
                                              const std::vector<std::string>& written) {
  namespace fs = std::filesystem;
  // Every file a run may or may not write (trajectory.txt, stats.csv and summary.json it always
  // writes).
  static const char* const kOptional[] = {"matches.png",       "residual_histogram.png",
                                          "ate_over_time.png", "rpe_over_time.png",
                                          "top_view.png",      "map.json",
                                          "map_frames.csv"};
  std::vector<std::string> removed;
  for (const char* name : kOptional) {
    const fs::path p = fs::path(dir) / name;
    if (std::find(written.begin(), written.end(), p.string()) != written.end()) continue;
    std::error_code error;
    if (fs::is_regular_file(p, error) && fs::remove(p, error)) removed.push_back(p.string());
  }
  return removed;
}

}  // namespace hbos::slam
