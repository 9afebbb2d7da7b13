#pragma once
/// \file
/// Running the tracker over a sequence, and what a run measured: the trajectory, per-frame
/// statistics, their totals, and the ATE/RPE against ground truth (through the evaluator in
/// eval/, called from trajectory_evaluation.cpp only).

#include "eval/evaluate.hpp"
#include "eval/trajectory.hpp"
#include "frontend/camera.hpp"
#include "frontend/config.hpp"
#include "frontend/frame.hpp"
#include "frontend/tracker.hpp"

#include <Eigen/Geometry>

#include <csignal>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace hbos::slam {

/// Totals over a run's frames.
struct RunTotals {
  int frames = 0;
  int frames_tracked = 0;       ///< frames with enough matches for a pose
  int frames_rough_ransac = 0;  ///< frames whose rough pose came from RANSAC
  long matches = 0;
  long person_matches = 0;
  long person_survivors = 0;
  long static_matches = 0;
  long static_dropped = 0;
  int frames_guarded = 0;  ///< frames where the leverage guard dropped matches
  long guard_dropped = 0;  ///< matches the leverage guard dropped (static or not)
  /// person_survivors / person_matches; nullopt without person matches.
  std::optional<double> person_survival_share;
  double static_loss_share = 0.0;  ///< static_dropped / static_matches
  double mean_screen_us = 0.0;     ///< [us] per frame with a screen (frames after the first)
  double mean_refine_us = 0.0;     ///< [us] per frame
  double mean_mask_us = 0.0;  ///< [us] per frame (all frames): the mask stage, detector included
  /// Medians of the same: on a shared machine a few preempted frames dominate the means.
  double median_screen_us = 0.0;
  double median_mask_us = 0.0;
};

[[nodiscard]] RunTotals total_of(const std::vector<FrameStats>& stats);

/// The frame shown in the figures: its images and what the tracker decided on it.
struct FigureFrame {
  Frame frame;
  TrackResult result;
};

struct RunResult {
  std::vector<double> stamps;            ///< [s] one per frame
  std::vector<Eigen::Isometry3d> poses;  ///< T_world_camera, the first frame = identity
  std::vector<FrameStats> stats;
  /// [us] per frame, the whole Tracker::track call (every stage after the mask); filled by
  /// run_tracker, empty where a tracker does not measure it.
  std::vector<double> track_us;
  RunTotals totals;
  std::optional<FigureFrame> figure;     ///< the frame chosen for the figures
  std::optional<Evaluation> evaluation;  ///< when the sequence has ground truth
  bool interrupted = false;              ///< stopped by `stop` before frame n-1
  /// Set when reading frame stats.size() failed (hbos::InvalidArgument: an image that cannot be
  /// decoded, a size that does not match): the run holds the frames before it. Callers that
  /// need every frame treat it as their error.
  std::optional<std::string> input_error;
};

/// Tracks frames 0 .. n-1 given by `frame_at` with a fresh Tracker. The figure frame is
/// `output.figure_frame`, or with -1 the one with the most person matches (else the middle one).
/// With `progress`, one line per frame is written to it. When `stop` is given and becomes
/// non-zero (a SIGINT handler sets it), the run ends after the frame in progress: the result
/// holds the frames done so far and `interrupted` is set. A frame that cannot be read ends the
/// run the same way, with `input_error` set.
[[nodiscard]] RunResult run_tracker(const std::function<Frame(int)>& frame_at, int n,
                                    const Config& config, const CameraModel& camera,
                                    std::ostream* progress,
                                    const volatile std::sig_atomic_t* stop = nullptr);

/// The ATE (SE(3)-aligned, as evaluate_ate.py) and, from 4 poses on, the per-frame RPE (delta
/// 1 frame) of the estimate against `groundtruth`; `frame_stamps` count the frames for the share
/// tracked.
/// Throws hbos::InvalidArgument when the two do not overlap.
[[nodiscard]] Evaluation evaluate_trajectory(const Trajectory& groundtruth,
                                             const Trajectory& estimate,
                                             const std::vector<double>& frame_stamps);

/// The run's estimate as a Trajectory named `name`: the frames whose pose is finite (a lost
/// frame of the map tracker has a NaN pose and is left out).
[[nodiscard]] Trajectory estimate_of(const RunResult& run, const std::string& name);

}  // namespace hbos::slam
