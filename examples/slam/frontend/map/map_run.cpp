#include "frontend/map/map_run.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <chrono>
#include <future>
#include <ostream>
#include <string>
#include <utility>

namespace hbos::slam {

namespace {

using Clock = std::chrono::steady_clock;

struct TimedFrame {
  Frame frame;
  double decode_us = 0.0;
};

TimedFrame read_timed(const std::function<Frame(int)>& frame_at, int i) {
  const auto start = Clock::now();
  TimedFrame t{frame_at(i), 0.0};
  t.decode_us =
      std::chrono::duration<double, std::micro>(Clock::now() - start).count() - t.frame.mask_us;
  return t;
}

void show_progress(std::ostream& out, ProgressStyle style, int done, int n, const FrameStats& s,
                   const MapFrameReport& r, int tracked, double elapsed_s) {
  const double fps = elapsed_s > 0.0 ? done / elapsed_s : 0.0;
  if (style == ProgressStyle::kLines) {
    out << fmt::format(
        "hbos-slam: frame {:>5}/{}  {:<11}  matches {:>4} (person {:>3})  kept {:>4}  "
        "keyframes {:>4}  points {:>6}  culled {:>5}{}\n",
        done, n, to_string(r.source), s.matches, s.person_matches, s.survivors, r.keyframes,
        r.live_points, r.culled_points, s.tracked ? "" : "  LOST (no pose)");
  } else {
    constexpr int kWidth = 30;
    const int filled = n > 0 ? kWidth * done / n : kWidth;
    out << fmt::format("\rhbos-slam [{}{}] {}/{}  {:.1f} fps  tracked {:.0f} %  keyframes {}  ",
                       std::string(static_cast<std::size_t>(filled), '#'),
                       std::string(static_cast<std::size_t>(kWidth - filled), '.'), done, n, fps,
                       100.0 * tracked / done, r.keyframes);
    if (done == n) out << "\n";
  }
  out.flush();
}

}  // namespace

StageTimes stage_times(const std::vector<MapFrameReport>& reports,
                       const std::vector<FrameStats>& stats, const std::vector<double>& decode_us,
                       double wall_s) {
  StageTimes t;
  const std::size_t n = reports.size();
  if (n == 0) return t;
  for (std::size_t i = 0; i < n; ++i) {
    const MapFrameReport& r = reports[i];
    t.decode_ms += i < decode_us.size() ? decode_us[i] : 0.0;
    t.segmentation_ms += i < stats.size() ? stats[i].mask_us : 0.0;
    t.extraction_ms += r.extract_us;
    t.tracking_ms += r.tracking_us;
    t.rough_pose_ms += r.rough_us;
    t.local_map_ms += r.local_map_us;
    t.refine_ms += r.refine_us;
    t.screen_ms += r.screen_us;
    t.map_ms += r.map_us;
  }
  const double per_frame_ms = 1e-3 / static_cast<double>(n);
  for (double* v : {&t.decode_ms, &t.segmentation_ms, &t.extraction_ms, &t.tracking_ms,
                    &t.rough_pose_ms, &t.local_map_ms, &t.refine_ms, &t.screen_ms, &t.map_ms}) {
    *v *= per_frame_ms;
  }
  t.motion_estimation_ms =
      t.extraction_ms + t.tracking_ms + t.rough_pose_ms + t.local_map_ms + t.refine_ms + t.map_ms;
  t.dynamic_removal_ms = t.screen_ms;
  t.sum_ms = t.decode_ms + t.segmentation_ms + t.motion_estimation_ms + t.dynamic_removal_ms;
  t.wall_ms = 1e3 * wall_s / static_cast<double>(n);
  t.fps = wall_s > 0.0 ? static_cast<double>(n) / wall_s : 0.0;
  return t;
}

MapRun run_map_tracker(const std::function<Frame(int)>& frame_at, int n, const Config& config,
                       const CameraModel& camera, std::ostream* progress, ProgressStyle style,
                       const volatile std::sig_atomic_t* stop) {
  MapTracker tracker(config, camera);
  MapRun out;
  RunResult& run = out.run;
  const int chosen = config.output.figure_frame;
  int best_person_matches = -1, tracked = 0;
  const auto start = Clock::now();
  std::future<TimedFrame> next;
  if (n > 0) next = std::async(std::launch::async, read_timed, std::cref(frame_at), 0);
  for (int i = 0; i < n; ++i) {
    TimedFrame current;
    try {
      current = next.get();  // rethrows a read error of frame i
    } catch (const InvalidArgument& e) {
      run.input_error = e.what();
      break;
    }
    if (stop != nullptr && *stop != 0) {
      run.interrupted = true;
      break;
    }
    if (i + 1 < n) next = std::async(std::launch::async, read_timed, std::cref(frame_at), i + 1);
    Frame& frame = current.frame;
    TrackResult result = tracker.track(frame);
    const MapFrameReport& report = tracker.last_report();
    run.stamps.push_back(frame.stamp);
    run.poses.push_back(result.T_world_camera);
    run.stats.push_back(result.stats);
    out.reports.push_back(report);
    out.decode_us.push_back(current.decode_us);
    const FrameStats& s = result.stats;
    tracked += s.tracked ? 1 : 0;
    out.relocalisations += report.source == TrackSource::kRelocalised ? 1 : 0;
    out.lost_frames += s.tracked ? 0 : 1;
    if (progress != nullptr) {
      show_progress(*progress, style, i + 1, n, s, report, tracked,
                    std::chrono::duration<double>(Clock::now() - start).count());
    }
    const bool take = chosen >= 0 ? i == chosen
                                  : (i > 0 && s.person_matches > best_person_matches &&
                                     (s.person_matches > 0 || i == n / 2));
    if (take) {
      best_person_matches = s.person_matches;
      run.figure = FigureFrame{std::move(frame), std::move(result)};
    }
  }
  if (next.valid()) next.wait();  // an interrupted run still owns the read in flight
  out.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  run.totals = total_of(run.stats);
  out.stages = stage_times(out.reports, run.stats, out.decode_us, out.wall_s);
  out.keyframes = tracker.map().keyframes();
  out.map_points = tracker.map().points_created();
  out.culled_points = tracker.map().culled_points();
  return out;
}

}  // namespace hbos::slam
