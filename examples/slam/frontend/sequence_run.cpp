#include "frontend/sequence_run.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <algorithm>
#include <chrono>
#include <ostream>
#include <utility>

namespace hbos::slam {

namespace {

double median_of(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2 == 1) return *middle;
  return 0.5 * (*middle + *std::max_element(values.begin(), middle));
}

}  // namespace

RunTotals total_of(const std::vector<FrameStats>& stats) {
  RunTotals t;
  std::vector<double> screen_times, mask_times;
  double screen_us = 0.0, refine_us = 0.0;
  int screened = 0;
  for (const FrameStats& s : stats) {
    ++t.frames;
    t.mean_mask_us += s.mask_us;
    mask_times.push_back(s.mask_us);
    t.frames_tracked += s.tracked ? 1 : 0;
    t.frames_rough_ransac += s.rough_from_ransac ? 1 : 0;
    t.matches += s.matches;
    t.person_matches += s.person_matches;
    t.person_survivors += s.person_survivors;
    t.static_matches += s.matches - s.person_matches;
    t.static_dropped += s.static_dropped;
    t.frames_guarded += s.guard_dropped > 0 ? 1 : 0;
    t.guard_dropped += s.guard_dropped;
    if (s.matches > 0) {
      ++screened;
      screen_us += s.screen_us;
      screen_times.push_back(s.screen_us);
      refine_us += s.refine_us;
    }
  }
  if (t.person_matches > 0) {
    t.person_survival_share =
        static_cast<double>(t.person_survivors) / static_cast<double>(t.person_matches);
  }
  if (t.static_matches > 0) {
    t.static_loss_share =
        static_cast<double>(t.static_dropped) / static_cast<double>(t.static_matches);
  }
  if (t.frames > 0) t.mean_mask_us /= t.frames;
  t.median_screen_us = median_of(screen_times);
  t.median_mask_us = median_of(mask_times);
  if (screened > 0) {
    t.mean_screen_us = screen_us / screened;
    t.mean_refine_us = refine_us / screened;
  }
  return t;
}

RunResult run_tracker(const std::function<Frame(int)>& frame_at, int n, const Config& config,
                      const CameraModel& camera, std::ostream* progress,
                      const volatile std::sig_atomic_t* stop) {
  Tracker tracker(config, camera);
  RunResult run;
  const int chosen = config.output.figure_frame;
  int best_person_matches = -1;
  for (int i = 0; i < n; ++i) {
    if (stop != nullptr && *stop != 0) {
      run.interrupted = true;
      break;
    }
    Frame frame;
    try {
      frame = frame_at(i);
    } catch (const InvalidArgument& e) {
      run.input_error = e.what();
      break;
    }
    const auto track_start = std::chrono::steady_clock::now();
    TrackResult result = tracker.track(frame);
    run.track_us.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - track_start)
            .count());
    run.stamps.push_back(frame.stamp);
    run.poses.push_back(result.T_world_camera);
    run.stats.push_back(result.stats);
    const FrameStats& s = result.stats;
    if (progress != nullptr) {
      *progress << fmt::format(
          "hbos-slam: frame {:>4}/{}  matches {:>4} (person {:>3})  kept {:>4} (person {:>3})  "
          "screen {:>6.0f} us{}\n",
          i + 1, n, s.matches, s.person_matches, s.survivors, s.person_survivors, s.screen_us,
          s.tracked ? "" : "  LOST (constant velocity)");
      progress->flush();
    }
    // The figure: a requested frame, else the one with the most person matches (the middle
    // frame when no frame has any).
    const bool take = chosen >= 0 ? i == chosen
                                  : (i > 0 && s.person_matches > best_person_matches &&
                                     (s.person_matches > 0 || i == n / 2));
    if (take) {
      best_person_matches = s.person_matches;
      run.figure = FigureFrame{std::move(frame), std::move(result)};
    }
  }
  run.totals = total_of(run.stats);
  return run;
}

Evaluation evaluate_trajectory(const Trajectory& groundtruth, const Trajectory& estimate,
                               const std::vector<double>& frame_stamps) {
  EvaluationParams params;
  // evaluate_rpe.py pairs pose i with i + 1 and drops the pair ending at the last pose: 2 pairs,
  // its minimum, need 4 poses.
  params.rpe = estimate.size() >= 4;
  params.rpe_delta = 1.0;
  params.rpe_unit = RpeDeltaUnit::kFrames;  // drift per frame: comparable across sequence lengths
  params.frame_stamps = frame_stamps;
  return evaluate(groundtruth, estimate, params);
}

Trajectory estimate_of(const RunResult& run, const std::string& name) {
  // A frame without a pose (the map tracker's lost frames carry NaN) is left out, never written.
  std::vector<double> stamps;
  std::vector<Eigen::Isometry3d> poses;
  for (std::size_t i = 0; i < run.poses.size() && i < run.stamps.size(); ++i) {
    if (!run.poses[i].matrix().allFinite()) continue;
    stamps.push_back(run.stamps[i]);
    poses.push_back(run.poses[i]);
  }
  return make_trajectory(name, std::move(stamps), poses);
}

}  // namespace hbos::slam
