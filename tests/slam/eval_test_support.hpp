#pragma once
// Helpers shared by the trajectory-evaluation tests: data paths, synthetic trajectories, known
// transforms and scratch directories.

#include "eval/trajectory.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace hbos::slam::test {

/// A file under tests/data/trajectory_eval/.
inline std::string eval_data(const std::string& relative) {
  return std::string(HBOS_TEST_DATA_DIR) + "/trajectory_eval/" + relative;
}

/// A rotation drawn uniformly (normalised Gaussian quaternion).
inline Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  return q.normalized().toRotationMatrix();
}

inline Eigen::Vector3d random_vector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> uniform(-scale, scale);
  return {uniform(rng), uniform(rng), uniform(rng)};
}

/// A smooth, non-planar trajectory of n poses every `period` seconds from t0: a camera moving on
/// a 3D Lissajous curve while turning, so positions span all three axes and orientations vary.
inline Trajectory synthetic_trajectory(Eigen::Index n, double t0, double period,
                                       const std::string& name = "synthetic") {
  std::vector<double> stamps;
  std::vector<Eigen::Isometry3d> poses;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * period;
    stamps.push_back(t0 + t);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() << 1.0 + 0.8 * std::sin(0.7 * t), -0.5 + 0.6 * std::sin(1.1 * t + 0.3),
        1.4 + 0.3 * std::cos(0.5 * t);
    pose.linear() = (Eigen::AngleAxisd(0.4 * t, Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(0.2 * std::sin(t), Eigen::Vector3d::UnitX()) *
                     Eigen::AngleAxisd(0.1 * t, Eigen::Vector3d::UnitY()))
                        .toRotationMatrix();
    poses.push_back(pose);
  }
  return make_trajectory(name, stamps, poses);
}

/// Every pose T_world_camera of `trajectory` mapped to a new world frame by the similarity
/// x ↦ s·R·x + t: positions s·R·p + t, orientations R·R_i. The camera-relative motion is
/// unchanged up to the scale s.
inline Trajectory transformed(const Trajectory& trajectory, const Eigen::Matrix3d& rotation,
                              const Eigen::Vector3d& translation, double scale) {
  std::vector<Eigen::Isometry3d> poses;
  for (Eigen::Index i = 0; i < trajectory.size(); ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = rotation * trajectory.rotation(i);
    pose.translation() = scale * (rotation * trajectory.positions.col(i)) + translation;
    poses.push_back(pose);
  }
  return make_trajectory(trajectory.name + " (transformed)", trajectory.stamps, poses);
}

/// A fresh directory under the system temp dir, removed with everything in it on destruction.
class ScratchDir {
 public:
  ScratchDir() {
    const auto tick = std::chrono::steady_clock::now().time_since_epoch().count();
    std::random_device entropy;
    path_ = std::filesystem::temp_directory_path() /
            ("hbos_eval_test_" + std::to_string(tick) + "_" + std::to_string(entropy()));
    std::filesystem::create_directories(path_);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace hbos::slam::test
