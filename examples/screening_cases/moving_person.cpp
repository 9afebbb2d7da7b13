#include "moving_person.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace hbos::cases {

MovingPeople::MovingPeople(const std::vector<SourcePerson>& people,
                           std::vector<PersonMotion> motions, hbos::PinholeCamerad camera,
                           const Eigen::Isometry3d& T_world_first, double first_stamp)
    : camera_(camera), first_stamp_(first_stamp) {
  for (const PersonMotion& m : motions) {
    const auto it = std::find_if(people.begin(), people.end(),
                                 [&](const SourcePerson& p) { return p.id == m.person; });
    if (it == people.end()) {
      throw InvalidArgument(fmt::format("person '{}' is not in the fr3 frame ({} people found)",
                                        m.person, people.size()));
    }
    if (!(m.scale > 0.0) || !std::isfinite(m.scale) || !(m.depth_m > 0.0) ||
        !std::isfinite(m.depth_m) || !m.start_px.allFinite() || !m.velocity_m_s.allFinite()) {
      throw InvalidArgument(fmt::format(
          "person '{}': scale {} and depth {} m must be finite and > 0, start and velocity finite",
          m.person, m.scale, m.depth_m));
    }
    Placed p;
    p.source = &*it;
    p.motion = m;
    p.anchor_world = T_world_first * camera_.back_project(m.start_px, m.depth_m);
    p.velocity_world = T_world_first.linear() * m.velocity_m_s;
    placed_.push_back(p);
  }
}

cv::Mat MovingPeople::composite(double stamp, const Eigen::Isometry3d& T_world_camera, cv::Mat& bgr,
                                cv::Mat& depth_m) const {
  cv::Mat label(bgr.size(), CV_8UC1, cv::Scalar(0));
  const Eigen::Isometry3d T_camera_world = T_world_camera.inverse();
  // Anchor of each person in this camera; drawn far to near so the nearer one occludes.
  std::vector<Eigen::Vector3d> anchors;
  for (const Placed& p : placed_)
    anchors.push_back(T_camera_world *
                      (p.anchor_world + p.velocity_world * (stamp - first_stamp_)));
  std::vector<std::size_t> order(placed_.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return anchors[a].z() > anchors[b].z(); });
  for (const std::size_t k : order) {
    const Placed& p = placed_[k];
    const Eigen::Vector3d& a = anchors[k];
    if (a.z() < 0.1) continue;  // behind or at the camera: not visible
    const Eigen::Vector2d centre = camera_.project(a);
    const double s = p.motion.scale * p.motion.depth_m / a.z();
    const hbos::slam::PersonCutout& cut = p.source->cut;
    const double cx = 0.5 * (cut.bgr.cols - 1), cy = 0.5 * (cut.bgr.rows - 1);
    const cv::Matx23d M(s, 0.0, centre.x() - s * cx, 0.0, s, centre.y() - s * cy);
    cv::Mat colour, weight, relative;
    cv::warpAffine(cut.bgr, colour, M, bgr.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
    cv::Mat mask_f;
    cut.mask.convertTo(mask_f, CV_32F, 1.0 / 255.0);
    cv::warpAffine(mask_f, weight, M, bgr.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
    // Nearest neighbour keeps depth holes as holes (the sensor saw nothing there either).
    cv::warpAffine(cut.relative_depth, relative, M, bgr.size(), cv::INTER_NEAREST,
                   cv::BORDER_CONSTANT);
    const auto z = static_cast<float>(a.z());
    const auto id = static_cast<std::uint8_t>(k + 1);
    for (int y = 0; y < bgr.rows; ++y) {
      const float* w = weight.ptr<float>(y);
      for (int x = 0; x < bgr.cols; ++x) {
        if (w[x] < 0.5f) continue;
        bgr.at<cv::Vec3b>(y, x) = colour.at<cv::Vec3b>(y, x);
        depth_m.at<float>(y, x) = relative.at<float>(y, x) * z;
        label.at<std::uint8_t>(y, x) = id;
      }
    }
  }
  return label;
}

}  // namespace hbos::cases
