#include "eval/tracked_share.hpp"

#include <hbos/error.hpp>

#include <algorithm>
#include <cmath>

namespace hbos::slam {

namespace {

TrackedShare span_of(Eigen::Index evaluated_poses, const Trajectory& gt) {
  check_trajectory(gt, "compute_tracked_share: ground truth");
  detail::require(gt.size() > 0, "compute_tracked_share: empty ground truth");
  detail::require(evaluated_poses >= 0, "compute_tracked_share: evaluated_poses must be >= 0, got ",
                  evaluated_poses);
  TrackedShare s;
  s.evaluated_poses = evaluated_poses;
  s.span_begin = gt.stamps.front();
  s.span_end = gt.stamps.back();
  return s;
}

}  // namespace

TrackedShare compute_tracked_share(Eigen::Index evaluated_poses, const Trajectory& gt,
                                   const std::vector<double>& frame_stamps) {
  TrackedShare s = span_of(evaluated_poses, gt);
  s.basis = "frame list";
  s.sequence_frames = static_cast<Eigen::Index>(
      std::count_if(frame_stamps.begin(), frame_stamps.end(),
                    [&](double t) { return t >= s.span_begin && t <= s.span_end; }));
  detail::require(s.sequence_frames > 0, "compute_tracked_share: none of the ", frame_stamps.size(),
                  " frame stamps lies in the ground-truth span [", s.span_begin, ", ", s.span_end,
                  "] s (frame list of another sequence?)");
  s.share = static_cast<double>(s.evaluated_poses) / static_cast<double>(s.sequence_frames);
  return s;
}

TrackedShare compute_tracked_share(Eigen::Index evaluated_poses, const Trajectory& gt,
                                   double frame_rate) {
  detail::require(std::isfinite(frame_rate) && frame_rate > 0.0,
                  "compute_tracked_share: frame_rate must be finite and > 0 [Hz], got ",
                  frame_rate);
  TrackedShare s = span_of(evaluated_poses, gt);
  s.basis = "frame rate";
  s.sequence_frames =
      static_cast<Eigen::Index>(std::floor((s.span_end - s.span_begin) * frame_rate)) + 1;
  s.share = static_cast<double>(s.evaluated_poses) / static_cast<double>(s.sequence_frames);
  return s;
}

}  // namespace hbos::slam
