#include "frontend/grid/grid_run.hpp"

#include "frontend/frame_source.hpp"
#include "frontend/grid/parallax.hpp"
#include "frontend/grid/run_cache.hpp"
#include "frontend/map/map_run.hpp"
#include "frontend/person_scenario.hpp"
#include "frontend/residual_screen.hpp"
#include "frontend/rough_pose.hpp"
#include "frontend/sequence_run.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>
#include <hbos/version.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <ostream>

namespace hbos::slam {

namespace {

/// Everything a run's result depends on: a cached run is reused only when this matches. The
/// library's version stands for the code (a release that changes a screen's decisions bumps it),
/// as in hbos-dynbench's cell keys.
std::string grid_run_settings(const Config& c, const PersonVariant& v, int frames) {
  return fmt::format(
      "dataset={} frames={} camera={} tracker={} person={} depth={} speed={} start={} mask={} "
      "screen={} rounds={} later_floor={} later_rigid={} mask_evidence={} track_history={} "
      "provisional_consensus={} guard={} forgetting={} rough={} ransac_px={} refit_check={} "
      "reloc_refit_check={} jump={} history_consensus={} rule={} features={} hbos={}.{}.{}",
      c.dataset.path, frames, c.dataset.camera, to_string(c.tracker), c.scenario.person_dir,
      v.depth_m, v.speed_px_per_frame, v.start_x_px, to_string(c.mask.source), c.screen.name,
      c.screen.rounds, later_rounds_gate_floor(c), later_rounds_rigid_field(c),
      c.screen.mask_evidence, c.screen.track_history, c.screen.provisional_consensus,
      to_json(c.guard).dump(), c.map.history.forgetting, to_string(c.rough_pose.method),
      c.rough_pose.ransac_threshold_px, c.rough_pose.check_refit, c.map.relocalisation.check_refit,
      to_json(c.jump_limit).dump(), c.rough_pose.history_consensus, kHistoryConsensusRule,
      c.extraction.features, kVersionMajor, kVersionMinor, kVersionPatch);
}

std::string grid_cache_file(const Config& c, const PersonVariant& v) {
  std::string name = fmt::format("{}_{}_{}_{}.json", to_string(c.tracker), v.name,
                                 to_string(c.mask.source), c.screen.name);
  std::replace(name.begin(), name.end(), ' ', '_');
  return name;
}

GridRun grid_track(const Config& config, const std::vector<Frame>& frames,
                   const RgbdSequence& sequence, const CameraModel& camera,
                   const PersonVariant& variant, const volatile std::sig_atomic_t* stop) {
  const auto frame_at = [&](int i) { return frames[static_cast<std::size_t>(i)]; };
  const int n = static_cast<int>(frames.size());
  const RunResult run =
      config.tracker == TrackerKind::kMap
          ? run_map_tracker(frame_at, n, config, camera, nullptr, ProgressStyle::kLines, stop).run
          : run_tracker(frame_at, n, config, camera, nullptr, stop);
  GridRun r;
  r.tracker = to_string(config.tracker);
  r.variant = variant.name;
  r.mask = to_string(config.mask.source);
  r.screen = config.screen.name;
  r.ate_rmse_m = r.rpe_trans_rmse_m = std::nan("");
  try {
    const Evaluation e =
        evaluate_trajectory(*sequence.groundtruth, estimate_of(run, "hbos-slam"), run.stamps);
    r.ate_rmse_m = e.ate.stats.rmse;
    if (e.rpe) r.rpe_trans_rmse_m = e.rpe->trans_m.rmse;
  } catch (const InvalidArgument&) {
    // Too few poses to evaluate: kept as NaN, reported as such.
  }
  const RunTotals& t = run.totals;
  r.frames = t.frames;
  r.frames_tracked = t.frames_tracked;
  r.matches = t.matches;
  r.person_matches = t.person_matches;
  r.person_survivors = t.person_survivors;
  r.static_matches = t.static_matches;
  r.static_dropped = t.static_dropped;
  for (const FrameStats& s : run.stats) {
    r.frame_person_matches.push_back(s.person_matches);
    r.frame_person_survivors.push_back(s.person_survivors);
  }
  return r;
}

}  // namespace

std::vector<MaskSource> grid_masks() {
  return {MaskSource::kNone, MaskSource::kDegraded, MaskSource::kDetector};
}

GridResult run_variant_grid(const Config& base, const RgbdSequence& sequence,
                            const CameraModel& camera, const std::string& cache_dir,
                            std::ostream* progress, const volatile std::sig_atomic_t* stop,
                            const std::vector<std::string>& screens) {
  if (!sequence.groundtruth) {
    throw InvalidArgument("the variant grid needs ground truth: '" + sequence.root +
                          "' has no groundtruth.txt");
  }
  GridResult result;
  result.tracker = to_string(base.tracker);
  int n = static_cast<int>(sequence.size());
  if (base.dataset.max_frames > 0) n = std::min(n, base.dataset.max_frames);
  result.frames = n;
  const cv::Size image = read_frame_images(sequence, 0, camera.depth_factor).bgr.size();
  const PersonCutout person = load_person_cutout(base.scenario.person_dir);
  const cv::Size cutout = person.bgr.size();
  std::vector<double> stamps = sequence.rgb_stamps();
  stamps.resize(static_cast<std::size_t>(n));
  for (const MaskSource mask : grid_masks()) result.masks.emplace_back(to_string(mask));
  result.screens = screens;
  std::filesystem::create_directories(cache_dir);

  const int total = static_cast<int>(semireal_variants(image.width, cutout.width).size() *
                                     grid_masks().size() * result.screens.size());
  for (const PersonVariant& variant : semireal_variants(image.width, cutout.width)) {
    Config config = base;
    config.scenario = with_variant(base.scenario, variant);
    config.output.figure_frame = 0;
    result.variants.push_back({variant, person_parallax_px(*sequence.groundtruth, stamps, camera,
                                                           config.scenario, person, image)});
    for (const MaskSource mask : grid_masks()) {
      config.mask.source = mask;
      std::optional<std::vector<Frame>> frames;  // read only when a run is not cached
      for (const std::string& screen : result.screens) {
        if (stop != nullptr && *stop != 0) return result;
        config.screen.select(screen);
        const std::string settings = grid_run_settings(config, variant, n);
        const std::string path =
            (std::filesystem::path(cache_dir) / grid_cache_file(config, variant)).string();
        std::optional<GridRun> run = read_cached_run(path, settings);
        const bool reused = run.has_value();
        if (!reused) {
          if (!frames) {
            FrameSource source(sequence, camera.depth_factor, config.scenario, config.mask);
            frames.emplace();
            for (int i = 0; i < n; ++i) frames->push_back(source.frame(i));
          }
          run = grid_track(config, *frames, sequence, camera, variant, stop);
          if (stop != nullptr && *stop != 0) return result;  // a partial run is not kept
          write_cached_run(path, *run, settings);
        }
        result.runs.push_back(*run);
        result.reused += reused ? 1 : 0;
        if (progress != nullptr) {
          *progress << fmt::format(
              "hbos-slam: grid {:>3}/{} {} | {:<16} mask {:<8} screen {:<9} ATE {:6.2f} cm  RPE "
              "{:5.2f} mm/frame  person kept {:>4}/{:<4}{}\n",
              result.runs.size(), total, result.tracker, variant.name, run->mask, run->screen,
              run->ate_rmse_m * 100.0, run->rpe_trans_rmse_m * 1000.0, run->person_survivors,
              run->person_matches, reused ? "  (cached)" : "");
          progress->flush();
        }
      }
    }
  }
  result.complete = true;
  return result;
}

}  // namespace hbos::slam
