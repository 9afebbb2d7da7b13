#include "frontend/grid/parallax.hpp"

#include "eval/associate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace hbos::slam {

std::vector<double> person_parallax_px(const Trajectory& groundtruth,
                                       const std::vector<double>& stamps, const CameraModel& camera,
                                       const ScenarioConfig& scenario, int image_width,
                                       int image_height, int cutout_width, int cutout_height) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> residual(stamps.size(), nan);
  std::vector<std::optional<Eigen::Isometry3d>> pose(stamps.size());
  for (const Match& m : associate(groundtruth.stamps, stamps)) {
    pose[static_cast<std::size_t>(m.est)] = groundtruth.pose(m.gt);
  }
  // The cut-out's left edge in frame i, as PersonCompositor::position rounds it.
  const auto left = [&](std::size_t i) {
    return static_cast<double>(
        std::lround(scenario.start_x_px + scenario.speed_px_per_frame * static_cast<double>(i)));
  };
  const double top = image_height - cutout_height;
  const double v = (std::max(top, 0.0) + image_height) / 2.0;
  for (std::size_t i = 1; i < stamps.size(); ++i) {
    if (!pose[i - 1] || !pose[i]) continue;
    const double x0 = std::max(left(i - 1), 0.0);
    const double x1 = std::min(left(i - 1) + cutout_width, static_cast<double>(image_width));
    if (x1 <= x0) continue;
    const double u = (x0 + x1) / 2.0;
    const double d = scenario.depth_m;
    const Eigen::Vector3d point_prev((u - camera.cx) / camera.fx * d,
                                     (v - camera.cy) / camera.fy * d, d);
    const Eigen::Vector3d point_cur = (pose[i]->inverse() * *pose[i - 1]) * point_prev;
    if (!(point_cur.z() > 0.0)) continue;
    const Eigen::Vector2d static_px(camera.fx * point_cur.x() / point_cur.z() + camera.cx,
                                    camera.fy * point_cur.y() / point_cur.z() + camera.cy);
    const Eigen::Vector2d person_px(u + (left(i) - left(i - 1)), v);
    residual[i] = (person_px - static_px).norm();
  }
  return residual;
}

}  // namespace hbos::slam
