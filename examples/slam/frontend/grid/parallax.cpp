#include "frontend/grid/parallax.hpp"

#include "eval/associate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

namespace hbos::slam {

std::vector<double> person_parallax_px(const Trajectory& groundtruth,
                                       const std::vector<double>& stamps, const CameraModel& camera,
                                       const ScenarioConfig& scenario, const PersonCutout& cutout,
                                       cv::Size image) {
  constexpr int kStep = 4;  // every 4th pixel of the silhouette, both ways
  std::vector<double> residual(stamps.size(), std::numeric_limits<double>::quiet_NaN());
  std::vector<std::optional<Eigen::Isometry3d>> pose(stamps.size());
  for (const Match& m : associate(groundtruth.stamps, stamps)) {
    pose[static_cast<std::size_t>(m.est)] = groundtruth.pose(m.gt);
  }
  // The cut-out's left edge in frame i, as PersonCompositor::position rounds it.
  const auto left = [&](std::size_t i) {
    return static_cast<int>(
        std::lround(scenario.start_x_px + scenario.speed_px_per_frame * static_cast<double>(i)));
  };
  const int top = image.height - cutout.mask.rows;
  const cv::Rect frame(0, 0, image.width, image.height);
  for (std::size_t i = 1; i < stamps.size(); ++i) {
    if (!pose[i - 1] || !pose[i]) continue;
    const Eigen::Isometry3d cur_from_prev = pose[i]->inverse() * *pose[i - 1];
    const int shift = left(i) - left(i - 1);
    std::vector<cv::Point2f> before, after;
    std::vector<double> depth;
    for (int v = 0; v < cutout.mask.rows; v += kStep) {
      for (int u = 0; u < cutout.mask.cols; u += kStep) {
        const float relative = cutout.relative_depth.at<float>(v, u);
        if (cutout.mask.at<std::uint8_t>(v, u) == 0 || !(relative > 0.0f)) continue;
        const cv::Point p(left(i - 1) + u, top + v);
        if (!frame.contains(p) || !frame.contains(cv::Point(p.x + shift, p.y))) continue;
        before.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
        after.emplace_back(static_cast<float>(p.x + shift), static_cast<float>(p.y));
        depth.push_back(static_cast<double>(relative) * scenario.depth_m);
      }
    }
    if (before.empty()) continue;
    before = undistort_pixels(camera, before);
    after = undistort_pixels(camera, after);
    std::vector<double> r;
    for (std::size_t k = 0; k < before.size(); ++k) {
      const double d = depth[k];
      const Eigen::Vector3d point =
          cur_from_prev * Eigen::Vector3d((before[k].x - camera.cx) / camera.fx * d,
                                          (before[k].y - camera.cy) / camera.fy * d, d);
      if (!(point.z() > 0.0)) continue;
      const double du = camera.fx * point.x() / point.z() + camera.cx - after[k].x;
      const double dv = camera.fy * point.y() / point.z() + camera.cy - after[k].y;
      r.push_back(std::hypot(du, dv));
    }
    if (r.empty()) continue;
    const auto middle = r.begin() + static_cast<std::ptrdiff_t>(r.size() / 2);
    std::nth_element(r.begin(), middle, r.end());
    residual[i] = *middle;
  }
  return residual;
}

}  // namespace hbos::slam
