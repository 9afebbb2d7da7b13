#pragma once
/// \file
/// Ground-truth camera poses at the frames' stamps, and the seeded perturbation that makes a
/// "rough pose from perturbed ground truth". The random numbers come from splitmix64 and are
/// turned into doubles here, not by <random>'s distributions (whose output the C++ standard leaves
/// to the implementation), so the cases are the same bytes with any standard library.

#include "eval/trajectory.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>

namespace hbos::cases {

/// T_world_camera at `stamp`: positions interpolated linearly, rotations by slerp between the two
/// ground-truth poses around it. Throws hbos::InvalidArgument when `stamp` lies outside the
/// trajectory.
[[nodiscard]] Eigen::Isometry3d interpolate_pose(const hbos::slam::Trajectory& groundtruth,
                                                 double stamp);

/// splitmix64 (Steele, Lea, Flood 2014): a tiny generator with a fully specified output.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  /// Uniform in [0, 1) with 53 random bits.
  double uniform();
  /// A uniformly distributed unit vector.
  Eigen::Vector3d unit_vector();

 private:
  std::uint64_t state_;
};

/// `T` moved by a rotation of exactly `rotation_deg` about a random axis and a translation of
/// exactly `translation_m` in a random direction (applied on the left, in the target camera's
/// frame), both drawn from `random`.
[[nodiscard]] Eigen::Isometry3d perturb(const Eigen::Isometry3d& T, double rotation_deg,
                                        double translation_m, SplitMix64& random);

/// Rotation angle [deg] and translation distance [m] between two poses.
struct PoseError {
  double rotation_deg = 0.0;
  double translation_m = 0.0;
};
[[nodiscard]] PoseError pose_error(const Eigen::Isometry3d& estimate,
                                   const Eigen::Isometry3d& truth);

}  // namespace hbos::cases
