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

/// evaluated_poses / sequence_frames, over the ground truth's time span.
struct TrackedShare {
  Eigen::Index evaluated_poses = 0;  ///< estimate poses that took part in the ATE (the pairs)
  Eigen::Index sequence_frames = 0;  ///< camera frames in the ground-truth span
  double share = 0.0;                ///< [-] evaluated_poses / sequence_frames, not clamped
  double span_begin = 0.0;           ///< [s] first ground-truth stamp
  double span_end = 0.0;             ///< [s] last ground-truth stamp
  /// How sequence_frames was obtained: "frame list" (counted) or "frame rate" (estimated).
  std::string basis;
};

/// Frames counted from the sequence's own frame list (the stamps of rgb.txt): exact, including
/// dropped frames. Frames within [first, last] ground-truth stamp count.
/// Throws hbos::InvalidArgument when no frame lies in the span.
[[nodiscard]] TrackedShare compute_tracked_share(Eigen::Index evaluated_poses, const Trajectory& gt,
                                                 const std::vector<double>& frame_stamps);

/// Frames estimated as floor(span × frame_rate) + 1. Overestimates when the recording dropped
/// frames (TUM fr3/walking_xyz: 827 associated frames in 28.8 s, where 30 Hz gives 865), so
/// prefer the frame-list overload when the sequence's rgb.txt is at hand.
/// Throws hbos::InvalidArgument unless frame_rate is finite and > 0.
[[nodiscard]] TrackedShare compute_tracked_share(Eigen::Index evaluated_poses, const Trajectory& gt,
                                                 double frame_rate);

}  // namespace hbos::slam
