#pragma once
/// \file
/// A timestamped camera trajectory in the TUM RGB-D benchmark convention.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace hbos::slam {

/// A camera trajectory as stored in TUM RGB-D files (`t tx ty tz qx qy qz qw`): pose i is
/// T_world_camera at time stamps[i], i.e. positions are camera centres in the world frame.
///
/// Invariant (established by read_tum_trajectory, checked by every evaluator through
/// check_trajectory): stamps strictly increase, positions and quaternions have one column per
/// stamp, every value is finite and no quaternion is zero.
///
/// Quaternions are kept exactly as read, rows (qx, qy, qz, qw), because the TUM scripts normalise
/// them only when they build a rotation (`transform44`); rotation() does the same.
struct Trajectory {
  std::string name;              ///< file name or label, used in messages, plots and reports
  std::vector<double> stamps;    ///< [s] strictly increasing
  Eigen::Matrix3Xd positions;    ///< [m] camera centre in the world frame, one column per pose
  Eigen::Matrix4Xd quaternions;  ///< rows qx, qy, qz, qw (file order), not normalised

  [[nodiscard]] Eigen::Index size() const { return static_cast<Eigen::Index>(stamps.size()); }

  /// R_world_camera of pose i, from the normalised quaternion.
  [[nodiscard]] Eigen::Matrix3d rotation(Eigen::Index i) const;

  /// T_world_camera of pose i.
  [[nodiscard]] Eigen::Isometry3d pose(Eigen::Index i) const;
};

/// Rotation matrix of a quaternion of any non-zero norm, computed as TUM's `transform44`:
/// q is scaled by sqrt(2 / q·q) and the matrix is read off the outer product, so the result is
/// the rotation of the normalised quaternion.
[[nodiscard]] Eigen::Matrix3d rotation_from_quaternion(double qx, double qy, double qz, double qw);

/// Throws hbos::InvalidArgument naming `what` and the first violated invariant of Trajectory.
void check_trajectory(const Trajectory& trajectory, const std::string& what);

/// Builds a trajectory from poses (T_world_camera) and stamps; used by the front end to hand its
/// estimate to the evaluator without a file round trip. Checks the invariant.
[[nodiscard]] Trajectory make_trajectory(std::string name, std::vector<double> stamps,
                                         const std::vector<Eigen::Isometry3d>& poses);

}  // namespace hbos::slam
