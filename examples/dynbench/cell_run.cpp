#include "dynbench/cell_run.hpp"

#include "common/atomic_file.hpp"
#include "frontend/camera.hpp"
#include "frontend/dataset.hpp"
#include "frontend/frame_source.hpp"
#include "frontend/map/map_run.hpp"
#include "frontend/run_outputs.hpp"
#include "frontend/sequence_run.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <vector>

namespace hbos::dynbench {

namespace fs = std::filesystem;

namespace {

double median_of(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), middle, v.end());
  if (v.size() % 2 == 1) return *middle;
  return 0.5 * (*middle + *std::max_element(v.begin(), middle));
}

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

double number_or_nan(const nlohmann::json& j) {
  return j.is_null() ? std::numeric_limits<double>::quiet_NaN() : j.get<double>();
}

// Table III's stages, medians over frames: the first frame only extracts, so motion and screen
// are taken over the frames after it.
void stage_times(const slam::RunResult& run, CellMetrics& m) {
  std::vector<double> mask, motion, screen;
  for (std::size_t i = 0; i < run.stats.size(); ++i) {
    const slam::FrameStats& s = run.stats[i];
    mask.push_back(s.mask_us / 1000.0);
    if (i == 0) continue;
    screen.push_back(s.screen_us / 1000.0);
    if (i < run.track_us.size()) motion.push_back((run.track_us[i] - s.screen_us) / 1000.0);
  }
  m.mask_ms = median_of(mask);
  m.motion_ms = median_of(motion);
  m.screen_ms = median_of(screen);
}

}  // namespace

std::optional<double> CellMetrics::dynamic_kept_share() const {
  if (dynamic_matches == 0) return std::nullopt;
  return static_cast<double>(dynamic_kept) / static_cast<double>(dynamic_matches);
}

double CellMetrics::static_dropped_share() const {
  return static_matches > 0
             ? static_cast<double>(static_dropped) / static_cast<double>(static_matches)
             : 0.0;
}

double CellMetrics::tracked_share() const {
  return frames > 0 ? static_cast<double>(frames_tracked) / frames : 0.0;
}

nlohmann::json to_json(const CellMetrics& m) {
  const auto kept = m.dynamic_kept_share();
  return {{"ate_rmse_m", m.ate_rmse_m},
          {"rpe_trans_m_per_frame", m.rpe_trans_m},
          {"rpe_rot_deg_per_frame", m.rpe_rot_deg},
          {"dynamic_matches", m.dynamic_matches},
          {"dynamic_kept", m.dynamic_kept},
          {"dynamic_kept_share", kept ? nlohmann::json(*kept) : nlohmann::json(nullptr)},
          {"static_matches", m.static_matches},
          {"static_dropped", m.static_dropped},
          {"static_dropped_share", m.static_dropped_share()},
          {"frames", m.frames},
          {"frames_tracked", m.frames_tracked},
          {"mask_ms_median", number_or_null(m.mask_ms)},
          {"motion_ms_median", number_or_null(m.motion_ms)},
          {"screen_ms_median", number_or_null(m.screen_ms)},
          {"wall_s", m.wall_s}};
}

CellMetrics metrics_from_json(const nlohmann::json& j) {
  CellMetrics m;
  m.ate_rmse_m = j.at("ate_rmse_m").get<double>();
  m.rpe_trans_m = j.at("rpe_trans_m_per_frame").get<double>();
  m.rpe_rot_deg = j.at("rpe_rot_deg_per_frame").get<double>();
  m.dynamic_matches = j.at("dynamic_matches").get<long>();
  m.dynamic_kept = j.at("dynamic_kept").get<long>();
  m.static_matches = j.at("static_matches").get<long>();
  m.static_dropped = j.at("static_dropped").get<long>();
  m.frames = j.at("frames").get<int>();
  m.frames_tracked = j.at("frames_tracked").get<int>();
  m.mask_ms = number_or_nan(j.at("mask_ms_median"));
  m.motion_ms = number_or_nan(j.at("motion_ms_median"));
  m.screen_ms = number_or_nan(j.at("screen_ms_median"));
  m.wall_s = j.at("wall_s").get<double>();
  return m;
}

std::string cell_dir(const BenchSettings& settings, const Cell& cell) {
  return (fs::path(settings.out_dir) / "cells" / cell.id()).string();
}

std::optional<CellMetrics> load_finished_cell(const BenchSettings& settings, const Cell& cell,
                                              const nlohmann::json& expected) {
  const fs::path file = fs::path(cell_dir(settings, cell)) / "cell.json";
  std::ifstream in(file);
  if (!in) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.at("settings") != expected) return std::nullopt;
    return metrics_from_json(j.at("metrics"));
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;  // a damaged file is a cell to run again
  }
}

std::optional<CellMetrics> run_cell(const BenchSettings& settings, const Cell& cell,
                                    const std::string& sequence_dir,
                                    const nlohmann::json& cell_settings,
                                    const volatile std::sig_atomic_t* stop) {
  const auto start = std::chrono::steady_clock::now();
  slam::Config config = settings.base;
  config.dataset.path = sequence_dir;
  config.dataset.camera = settings.camera;
  config.dataset.max_frames = settings.frames;
  config.scenario.add_person = false;  // the rendered people are the dynamic objects
  config.scenario.objects_dir = (fs::path(sequence_dir) / "objects").string();
  config.mask.source = cell.mask == "none" ? slam::MaskSource::kNone : slam::MaskSource::kFiles;
  config.mask.files_dir = (fs::path(sequence_dir) / "masks" / cell.mask).string();
  config.mask.files_convention = slam::MaskConvention::kDynaSlam;
  config.mask.files_max_difference = config.dataset.max_association_difference;
  config.screen.select(cell.screen);
  config.output.dir = cell_dir(settings, cell);
  config.output.figure_frame = -1;  // the frame with the most dynamic matches
  config.output.progress = false;

  const slam::CameraModel camera = slam::load_camera(settings.camera);
  const slam::RgbdSequence sequence =
      slam::load_tum_sequence(sequence_dir, config.dataset.max_association_difference);
  if (!sequence.groundtruth) {
    throw InvalidArgument(fmt::format("sequence '{}' has no groundtruth.txt", sequence_dir));
  }
  slam::FrameSource source(sequence, camera.depth_factor, config.scenario, config.mask);
  int n = source.size();
  if (settings.frames > 0) n = std::min(n, settings.frames);
  const auto frame_at = [&](int i) { return source.frame(i); };

  slam::RunResult run;
  std::optional<slam::MapRun> map_run;
  if (config.tracker == slam::TrackerKind::kMap) {
    map_run = slam::run_map_tracker(frame_at, n, config, camera, nullptr,
                                    slam::ProgressStyle::kLines, stop);
    run = std::move(map_run->run);
  } else {
    run = slam::run_tracker(frame_at, n, config, camera, nullptr, stop);
  }
  if (run.input_error) throw InvalidArgument(*run.input_error);
  if (run.interrupted || (stop != nullptr && *stop != 0)) return std::nullopt;
  run.evaluation = slam::evaluate_trajectory(*sequence.groundtruth,
                                             slam::estimate_of(run, "hbos-slam"), run.stamps);

  CellMetrics m;
  const slam::Evaluation& e = *run.evaluation;
  m.ate_rmse_m = e.ate.stats.rmse;
  m.rpe_trans_m = e.rpe ? e.rpe->trans_m.rmse : std::numeric_limits<double>::quiet_NaN();
  m.rpe_rot_deg = e.rpe ? e.rpe->rot_deg.rmse : std::numeric_limits<double>::quiet_NaN();
  const slam::RunTotals& t = run.totals;
  m.dynamic_matches = t.person_matches;
  m.dynamic_kept = t.person_survivors;
  m.static_matches = t.static_matches;
  m.static_dropped = t.static_dropped;
  m.frames = t.frames;
  m.frames_tracked = t.frames_tracked;
  stage_times(run, m);
  if (map_run) {  // the map tracker times its own stages (means, Table III's grouping)
    m.motion_ms = map_run->stages.motion_estimation_ms;
    m.screen_ms = map_run->stages.dynamic_removal_ms;
  }

  slam::write_run_outputs(config.output.dir, run, config, camera.name, &*sequence.groundtruth);
  m.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::json j = {{"settings", cell_settings}, {"metrics", to_json(m)}};
  examples::write_file_atomically(fs::path(config.output.dir) / "cell.json", j.dump(1) + "\n");
  return m;
}

}  // namespace hbos::dynbench
