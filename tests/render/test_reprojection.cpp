// The ground truth agrees with itself: pixel, depth, pose and intrinsics give the rendered
// surface point, and that point seen from the next frame's pose lands on the same surface point.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/sequence.hpp"

using namespace hbos::render;

namespace {

Eigen::Vector3d back_project(const Intrinsics& K, const Pose& T_wc, double u, double v, double z) {
  const Eigen::Vector3d pc((u - K.cx) / K.fx * z, (v - K.cy) / K.fy * z, z);
  return T_wc * pc;
}

// Bilinear sample of a CV_32FC3 image at (u, v); false if any of the 4 taps is not static or
// not on the same smooth surface (so the interpolation is meaningful).
bool sample_world(const RenderedView& view, double u, double v, Eigen::Vector3d& out) {
  const int u0 = static_cast<int>(std::floor(u)), v0 = static_cast<int>(std::floor(v));
  if (u0 < 1 || v0 < 1 || u0 + 2 >= view.depth.cols || v0 + 2 >= view.depth.rows) return false;
  const double a = u - u0, b = v - v0;
  Eigen::Vector3d acc = Eigen::Vector3d::Zero();
  const float z00 = view.depth.at<float>(v0, u0);
  for (int dv = 0; dv <= 1; ++dv) {
    for (int du = 0; du <= 1; ++du) {
      const float z = view.depth.at<float>(v0 + dv, u0 + du);
      if (view.object_id.at<unsigned char>(v0 + dv, u0 + du) != 0 || z <= 0.f) return false;
      if (std::abs(z - z00) > 0.01f * z00) return false;
      const cv::Vec3f w = view.world.at<cv::Vec3f>(v0 + dv, u0 + du);
      const double wgt = (du ? a : 1 - a) * (dv ? b : 1 - b);
      acc += wgt * Eigen::Vector3d(w[0], w[1], w[2]);
    }
  }
  out = acc;
  return true;
}

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))];
}

}  // namespace

TEST_CASE(
    "a static pixel reprojected with ground-truth depth and poses lands on its surface point") {
  for (const char* scenario : {"walking_xyz", "walking_rpy"}) {
    SequenceOptions o;
    o.scenario = scenario;
    o.frames = 40;
    SequenceRenderer r(o);
    const Intrinsics& K = o.K;
    for (int i : {5, 30}) {
      const RenderedView a = r.render_truth(i);
      const RenderedView b = r.render_truth(i + 1);
      const Pose& Ta = r.poses()[static_cast<std::size_t>(i)].pose;
      const Pose& Tb = r.poses()[static_cast<std::size_t>(i + 1)].pose;
      std::vector<double> self_px, next_px;
      for (int v = 4; v < K.height - 4; v += 7) {
        for (int u = 4; u < K.width - 4; u += 7) {
          const float z = a.depth.at<float>(v, u);
          if (z <= 0.f || a.object_id.at<unsigned char>(v, u) != 0) continue;
          // 1. Pixel centre + depth + pose = the rendered world point (intrinsics, pixel-centre
          //    convention and pose direction all agree).
          const Eigen::Vector3d X = back_project(K, Ta, u, v, z);
          const cv::Vec3f w = a.world.at<cv::Vec3f>(v, u);
          self_px.push_back((X - Eigen::Vector3d(w[0], w[1], w[2])).norm() * K.fx / z);
          // 2. Into the next frame: project, sample that frame's surface there, compare.
          const Eigen::Vector3d pc = Tb.inverse() * X;
          if (pc.z() <= 0.1) continue;
          const double ub = K.fx * pc.x() / pc.z() + K.cx, vb = K.fy * pc.y() / pc.z() + K.cy;
          Eigen::Vector3d Y;
          if (!sample_world(b, ub, vb, Y)) continue;
          // Occluded in the next frame: the surface there is nearer than X.
          if ((Tb.inverse() * Y).z() < pc.z() - 0.02) continue;
          next_px.push_back((X - Y).norm() * K.fx / pc.z());
        }
      }
      INFO(scenario << " frame " << i << ": " << self_px.size() << " / " << next_px.size()
                    << " pixels");
      REQUIRE(self_px.size() > 1000);
      REQUIRE(next_px.size() > 1000);
      // float32 world positions and depth: ~1e-3 px; a half-pixel convention error is 0.5 px.
      CHECK(percentile(self_px, 0.5) < 0.02);
      CHECK(percentile(self_px, 0.95) < 0.05);
      CHECK(percentile(next_px, 0.5) < 0.05);
      CHECK(percentile(next_px, 0.95) < 0.2);
    }
  }
}

TEST_CASE("resampling reproduces the ground truth at its own stamps and starts at its first") {
  const auto gt =
      read_tum_trajectory(default_data_dir() / "trajectories" / "fr3_walking_xyz_groundtruth.txt");
  const auto r = resample(gt, 30.0, 0);
  REQUIRE(r.front().stamp == gt.front().stamp);
  CHECK(r.front().pose.isApprox(gt.front().pose, 1e-12));
  CHECK(r.back().stamp <= gt.back().stamp);
  CHECK(gt.back().stamp - r.back().stamp < 1.0 / 30.0);
  // ~28.8 s at 30 Hz.
  CHECK(r.size() ==
        static_cast<std::size_t>(std::floor((gt.back().stamp - gt.front().stamp) * 30.0)) + 1);
  for (std::size_t i = 1; i < r.size(); ++i) {
    REQUIRE(std::abs(r[i].stamp - r[i - 1].stamp - 1.0 / 30.0) < 1e-6);
  }
}
