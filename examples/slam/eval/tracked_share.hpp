#pragma once
/// \file
/// The share of a sequence that a run tracked, as DynaSLAM reports next to monocular ATE
/// ("87 % tracked"): an ATE over a few well-tracked seconds is not comparable with one over the
/// whole sequence.

#include "eval/trajectory.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace hbos::slam {

/// evaluated_poses / sequence_frames, over the ground truth's time span; never above 1.
struct TrackedShare {
  Eigen::Index evaluated_poses = 0;  ///< estimate poses that took part in the ATE (the pairs)
  Eigen::Index sequence_frames = 0;  ///< camera frames in the ground-truth span
  double share = 0.0;                ///< [-] evaluated_poses / sequence_frames, in [0, 1]
  double span_begin = 0.0;           ///< [s] first ground-truth stamp
  double span_end = 0.0;             ///< [s] last ground-truth stamp
  double frame_period = 0.0;         ///< [s] "estimate spacing" only: median estimate Δt
  /// How sequence_frames was obtained: "frame list" (counted from rgb.txt) or "estimate
  /// spacing" (the evaluated poses plus the frames missing from the gaps in their stamps).
  std::string basis;
};

/// The largest frame count either overload accepts: 1e9 frames is 1 year at 30 Hz; more is a
/// corrupted stamp, not a sequence.
inline constexpr double kMaxSequenceFrames = 1e9;

/// Frames counted from the sequence's own frame list (the stamps of rgb.txt): exact, including
/// dropped frames. Frames within [first, last] ground-truth stamp count.
/// Throws hbos::InvalidArgument when no frame lies in the span, or when more poses were evaluated
/// than the list has frames in the span (the list of another sequence: the share would exceed
/// 100 %).
[[nodiscard]] TrackedShare compute_tracked_share(Eigen::Index evaluated_poses, const Trajectory& gt,
                                                 const std::vector<double>& frame_stamps);

/// Without a frame list, the frames are counted from the estimate itself: `evaluated_stamps`
/// (the estimate stamps that took part in the ATE, on the ground-truth clock, sorted) give the
/// frame period as the median of their differences; every gap longer than a period holds
/// round(gap / period) − 1 untracked frames, and so do the stretches between the ground truth's
/// ends and the first and last evaluated pose (floor(stretch / period)). The share therefore
/// never exceeds 1. A run that lost tracking for most of the sequence at a lower rate than it
/// ran is measured as well as its own timing allows: pass the frame list for the exact count.
/// Throws hbos::InvalidArgument on fewer than 2 evaluated stamps, unsorted or non-finite stamps,
/// or a count above kMaxSequenceFrames.
[[nodiscard]] TrackedShare compute_tracked_share(const std::vector<double>& evaluated_stamps,
                                                 const Trajectory& gt);

}  // namespace hbos::slam
