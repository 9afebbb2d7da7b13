#include "eval/trajectory.hpp"

#include <hbos/error.hpp>

#include <cmath>
#include <cstddef>
#include <utility>

namespace hbos::slam {

Eigen::Matrix3d rotation_from_quaternion(double qx, double qy, double qz, double qw) {
  const double norm2 = qx * qx + qy * qy + qz * qz + qw * qw;
  detail::require(norm2 > 0.0 && std::isfinite(norm2),
                  "rotation_from_quaternion: quaternion must be finite and non-zero, got (", qx,
                  ", ", qy, ", ", qz, ", ", qw, ")");
  // Scaling by sqrt(2/n) folds the normalisation and the factor 2 of the textbook formula into
  // the outer product, exactly as transform44 does; the term order below matches it too.
  const double s = std::sqrt(2.0 / norm2);
  const double x = qx * s;
  const double y = qy * s;
  const double z = qz * s;
  const double w = qw * s;
  Eigen::Matrix3d r;
  r << 1.0 - y * y - z * z, x * y - z * w, x * z + y * w,  //
      x * y + z * w, 1.0 - x * x - z * z, y * z - x * w,   //
      x * z - y * w, y * z + x * w, 1.0 - x * x - y * y;
  return r;
}

Eigen::Matrix3d Trajectory::rotation(Eigen::Index i) const {
  return rotation_from_quaternion(quaternions(0, i), quaternions(1, i), quaternions(2, i),
                                  quaternions(3, i));
}

Eigen::Isometry3d Trajectory::pose(Eigen::Index i) const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = rotation(i);
  t.translation() = positions.col(i);
  return t;
}

void check_trajectory(const Trajectory& trajectory, const std::string& what) {
  const Eigen::Index n = trajectory.size();
  detail::require(trajectory.positions.cols() == n && trajectory.quaternions.cols() == n, what,
                  " '", trajectory.name, "': ", n, " stamps but ", trajectory.positions.cols(),
                  " positions and ", trajectory.quaternions.cols(), " quaternions");
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = trajectory.stamps[static_cast<std::size_t>(i)];
    detail::require(std::isfinite(t), what, " '", trajectory.name, "': pose ", i,
                    " has a non-finite stamp ", t);
    if (i > 0) {
      const double previous = trajectory.stamps[static_cast<std::size_t>(i - 1)];
      detail::require(t > previous, what, " '", trajectory.name,
                      "': stamps must strictly increase, ", "but pose ", i, " has ", t, " after ",
                      previous);
    }
    detail::require(trajectory.positions.col(i).allFinite(), what, " '", trajectory.name,
                    "': pose ", i, " has a non-finite position");
    detail::require(trajectory.quaternions.col(i).allFinite() &&
                        trajectory.quaternions.col(i).squaredNorm() > 0.0,
                    what, " '", trajectory.name, "': pose ", i,
                    " has a non-finite or zero quaternion");
  }
}

Trajectory make_trajectory(std::string name, std::vector<double> stamps,
                           const std::vector<Eigen::Isometry3d>& poses) {
  detail::require(stamps.size() == poses.size(), "make_trajectory '", name, "': ", stamps.size(),
                  " stamps but ", poses.size(), " poses");
  Trajectory trajectory;
  trajectory.name = std::move(name);
  trajectory.stamps = std::move(stamps);
  const auto n = static_cast<Eigen::Index>(poses.size());
  trajectory.positions.resize(3, n);
  trajectory.quaternions.resize(4, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Isometry3d& t = poses[static_cast<std::size_t>(i)];
    trajectory.positions.col(i) = t.translation();
    const Eigen::Quaterniond q(t.linear());
    trajectory.quaternions.col(i) << q.x(), q.y(), q.z(), q.w();
  }
  check_trajectory(trajectory, "make_trajectory");
  return trajectory;
}

}  // namespace hbos::slam
