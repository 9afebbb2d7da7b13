#pragma once
/// \file
/// How far the composited person's image motion is from the flow the camera's own motion gives a
/// static point at the person's depth (issue 7 item 9). Where the two nearly agree, the person's
/// reprojection residuals are as small as a static point's and no screen on them can tell.

#include "eval/trajectory.hpp"
#include "frontend/camera.hpp"
#include "frontend/config.hpp"

#include <vector>

namespace hbos::slam {

/// A frame counts as "parallax-hidden" when the person's residual under the true motion is below
/// ORB-SLAM2's chi-square gate at pyramid level 0, sqrt(5.991) x 1 px (rule fixed in advance).
inline constexpr double kHiddenParallaxPx = 2.447;

/// Per frame i (entry 0 is NaN): the residual [px] of the person's centre between frames i-1 and
/// i under the ground-truth camera motion: the centre of the cut-out's visible box in frame i-1,
/// back-projected at the person's median depth (pinhole, distortion ignored), moved by
/// T_cur_prev from `groundtruth` (the pose nearest each stamp) and projected, minus where the
/// person's motion puts it. NaN where a stamp has no ground truth within 0.02 s or the person is
/// out of view. `image` is the frames' size, `cutout` the cut-out's.
[[nodiscard]] std::vector<double> person_parallax_px(const Trajectory& groundtruth,
                                                     const std::vector<double>& stamps,
                                                     const CameraModel& camera,
                                                     const ScenarioConfig& scenario,
                                                     int image_width, int image_height,
                                                     int cutout_width, int cutout_height);

}  // namespace hbos::slam
