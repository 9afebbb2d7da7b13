#pragma once
/// \file
/// Running the map tracker over a sequence: the same RunResult as run_tracker() (so outputs,
/// figures and evaluation are shared), plus what only the map tracker measures — per-frame stage
/// times, decode time, map statistics — and the wall-clock rate. The next frame is read and
/// masked on a second thread while the current one is tracked (one read at a time, so the frame
/// source needs no locking).

#include "frontend/camera.hpp"
#include "frontend/config.hpp"
#include "frontend/frame.hpp"
#include "frontend/map/map_tracker.hpp"
#include "frontend/sequence_run.hpp"

#include <csignal>
#include <functional>
#include <iosfwd>
#include <vector>

namespace hbos::slam {

/// How progress is shown on `progress`.
enum class ProgressStyle {
  kLines,  ///< one line per frame (a log or a pipe)
  kBar,    ///< one bar redrawn in place with '\r' (a terminal)
};

/// Mean milliseconds per frame, in the grouping of the HBOS paper's Table III.
struct StageTimes {
  double decode_ms = 0.0;        ///< image decode (and compositing the person, if any)
  double segmentation_ms = 0.0;  ///< the dynamic-object mask (detector, when it is the mask)
  double extraction_ms = 0.0;    ///< ORB
  double tracking_ms = 0.0;      ///< lightweight tracking / relocalisation
  double rough_pose_ms = 0.0;    ///< PnP RANSAC
  double local_map_ms = 0.0;     ///< local map selection and projection matching
  double refine_ms = 0.0;        ///< pose optimisation (rounds and final)
  double screen_ms = 0.0;        ///< the residual screen
  double map_ms = 0.0;           ///< screening history, culling, keyframes
  /// Table III: motion estimation = extraction + tracking + rough pose + local map + refine + map.
  double motion_estimation_ms = 0.0;
  /// Table III: dynamic point detection and removal = the screen.
  double dynamic_removal_ms = 0.0;
  double sum_ms = 0.0;   ///< every stage above, decode included
  double wall_ms = 0.0;  ///< wall clock per frame (decode overlaps tracking on a second thread)
  double fps = 0.0;      ///< frames per second, wall clock
};

struct MapRun {
  RunResult run;
  std::vector<MapFrameReport> reports;  ///< one per frame
  std::vector<double> decode_us;        ///< [us] per frame: reading (and compositing), no mask
  double wall_s = 0.0;                  ///< [s] the whole loop
  StageTimes stages;
  int keyframes = 0;
  int map_points = 0;  ///< created
  int culled_points = 0;
  int relocalisations = 0;
  int lost_frames = 0;
};

/// Tracks frames 0 .. n-1 with a fresh MapTracker. The figure frame is chosen as run_tracker()
/// chooses it. With `progress`, progress goes there in `style`; when `stop` becomes non-zero the
/// run ends after the frame in progress (`run.interrupted`).
[[nodiscard]] MapRun run_map_tracker(const std::function<Frame(int)>& frame_at, int n,
                                     const Config& config, const CameraModel& camera,
                                     std::ostream* progress, ProgressStyle style,
                                     const volatile std::sig_atomic_t* stop = nullptr);

/// The stage means of `reports` (frames with a report), `decode_us` and the wall time.
[[nodiscard]] StageTimes stage_times(const std::vector<MapFrameReport>& reports,
                                     const std::vector<FrameStats>& stats,
                                     const std::vector<double>& decode_us, double wall_s);

}  // namespace hbos::slam
