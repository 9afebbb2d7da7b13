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
  detail::require(s.evaluated_poses <= s.sequence_frames,
                  "compute_tracked_share: ", s.evaluated_poses,
                  " poses were evaluated but the frame list has only ", s.sequence_frames,
                  " frames in the ground-truth span [", s.span_begin, ", ", s.span_end,
                  "] s (frame list of another sequence?)");
  s.share = static_cast<double>(s.evaluated_poses) / static_cast<double>(s.sequence_frames);
  return s;
}

TrackedShare compute_tracked_share(const std::vector<double>& evaluated_stamps,
                                   const Trajectory& gt) {
  const auto n = static_cast<Eigen::Index>(evaluated_stamps.size());
  TrackedShare s = span_of(n, gt);
  s.basis = "estimate spacing";
  detail::require(n >= 2, "compute_tracked_share: cannot count frames from ", n,
                  " evaluated pose(s); pass the sequence's frame list (--frames rgb.txt)");
  std::vector<double> gaps;
  gaps.reserve(evaluated_stamps.size() - 1);
  for (std::size_t i = 0; i < evaluated_stamps.size(); ++i) {
    detail::require(std::isfinite(evaluated_stamps[i]), "compute_tracked_share: evaluated stamp ",
                    i, " is not finite");
    if (i > 0) {
      const double gap = evaluated_stamps[i] - evaluated_stamps[i - 1];
      detail::require(gap > 0.0, "compute_tracked_share: evaluated stamps must increase, stamp ", i,
                      " (", evaluated_stamps[i], ") follows ", evaluated_stamps[i - 1]);
      gaps.push_back(gap);
    }
  }
  std::vector<double> sorted = gaps;
  const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), middle, sorted.end());
  const double period = *middle;
  s.frame_period = period;
  // Counted in double, so that no corrupt stamp can overflow an integer before the check.
  double missing = 0.0;
  for (const double gap : gaps) missing += std::max(0.0, std::round(gap / period) - 1.0);
  missing += std::max(0.0, std::floor((evaluated_stamps.front() - s.span_begin) / period));
  missing += std::max(0.0, std::floor((s.span_end - evaluated_stamps.back()) / period));
  const double frames = static_cast<double>(n) + missing;
  detail::require(std::isfinite(frames) && frames <= kMaxSequenceFrames,
                  "compute_tracked_share: the estimate's stamps (median spacing ", period,
                  " s over a ", s.span_end - s.span_begin,
                  " s ground-truth span) imply more than 1e9 frames; check the stamps or pass "
                  "--frames rgb.txt");
  s.sequence_frames = static_cast<Eigen::Index>(frames);
  s.share = static_cast<double>(n) / frames;
  return s;
}

}  // namespace hbos::slam
