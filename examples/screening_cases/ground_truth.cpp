#include "ground_truth.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <algorithm>
#include <cmath>

namespace hbos::cases {

Eigen::Isometry3d interpolate_pose(const hbos::slam::Trajectory& groundtruth, double stamp) {
  const std::vector<double>& t = groundtruth.stamps;
  if (t.empty() || stamp < t.front() || stamp > t.back()) {
    throw InvalidArgument(
        fmt::format("ground truth '{}' does not cover stamp {:.6f}", groundtruth.name, stamp));
  }
  const auto upper = std::upper_bound(t.begin(), t.end(), stamp);
  const auto j = static_cast<Eigen::Index>(
      std::min<std::ptrdiff_t>(upper - t.begin(), static_cast<std::ptrdiff_t>(t.size()) - 1));
  const Eigen::Index i = j > 0 ? j - 1 : 0;
  const double span = t[static_cast<std::size_t>(j)] - t[static_cast<std::size_t>(i)];
  const double w = span > 0.0 ? (stamp - t[static_cast<std::size_t>(i)]) / span : 0.0;
  const Eigen::Quaterniond qi(groundtruth.rotation(i)), qj(groundtruth.rotation(j));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = qi.slerp(w, qj).toRotationMatrix();
  T.translation() = (1.0 - w) * groundtruth.positions.col(i) + w * groundtruth.positions.col(j);
  return T;
}

std::uint64_t SplitMix64::next() {
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double SplitMix64::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

Eigen::Vector3d SplitMix64::unit_vector() {
  // Archimedes: z uniform in [-1, 1] and the azimuth uniform give a uniform point on the sphere.
  const double z = 2.0 * uniform() - 1.0;
  const double phi = 2.0 * M_PI * uniform();
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Eigen::Isometry3d perturb(const Eigen::Isometry3d& T, double rotation_deg, double translation_m,
                          SplitMix64& random) {
  const Eigen::Vector3d axis = random.unit_vector();
  const Eigen::Vector3d direction = random.unit_vector();
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  delta.linear() = Eigen::AngleAxisd(rotation_deg * M_PI / 180.0, axis).toRotationMatrix();
  delta.translation() = translation_m * direction;
  return delta * T;
}

PoseError pose_error(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth) {
  const Eigen::Isometry3d d = estimate * truth.inverse();
  const double c = std::clamp(0.5 * (d.linear().trace() - 1.0), -1.0, 1.0);
  return {std::acos(c) * 180.0 / M_PI, d.translation().norm()};
}

}  // namespace hbos::cases
