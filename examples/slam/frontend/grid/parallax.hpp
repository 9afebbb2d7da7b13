#pragma once
/// \file
/// How far the composited person's image motion is from the flow the camera's own motion gives a
/// static point at the person's depth (issue 7 item 9). Where the two nearly agree, the person's
/// reprojection residuals are as small as a static point's and no screen on them can tell.

#include "eval/trajectory.hpp"
#include "frontend/camera.hpp"
#include "frontend/config.hpp"
#include "frontend/person_scenario.hpp"

#include <opencv2/core.hpp>

#include <vector>

namespace hbos::slam {

/// A frame counts as "parallax-hidden" when the person's residual under the true motion is below
/// ORB-SLAM2's chi-square gate at pyramid level 0, sqrt(5.991) x 1 px (rule fixed in advance).
inline constexpr double kHiddenParallaxPx = 2.447;

/// Per frame i (entry 0 is NaN): the residual [px] the person has between frames i-1 and i under
/// the ground-truth camera motion, the median over its silhouette: every 4th pixel of the
/// cut-out's mask that is in view in both frames and has depth, undistorted, back-projected at
/// its composited depth in frame i-1, moved by T_cur_prev from `groundtruth` (the pose nearest
/// each stamp) and projected, against where the person's image motion puts it (undistorted).
/// NaN where a stamp has no ground truth within 0.02 s or no such pixel exists. `image` is the
/// frames' size.
[[nodiscard]] std::vector<double> person_parallax_px(const Trajectory& groundtruth,
                                                     const std::vector<double>& stamps,
                                                     const CameraModel& camera,
                                                     const ScenarioConfig& scenario,
                                                     const PersonCutout& cutout, cv::Size image);

}  // namespace hbos::slam
