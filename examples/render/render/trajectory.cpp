#include "render/trajectory.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace hbos::render {

std::vector<StampedPose> read_tum_trajectory(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError("cannot open trajectory file " + file.string());
  std::vector<StampedPose> out;
  std::string line;
  int line_no = 0;
  static const char* const kFields[] = {"timestamp", "tx", "ty", "tz", "qx", "qy", "qz", "qw"};
  while (std::getline(in, line)) {
    ++line_no;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream ss(line);
    double v[8];
    for (int k = 0; k < 8; ++k) {
      if (!(ss >> v[k]) || !std::isfinite(v[k])) {
        throw InputError(file.string() + ":" + std::to_string(line_no) + ": field '" + kFields[k] +
                         "' is missing or not a finite number");
      }
    }
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    const double n = q.norm();
    if (std::abs(n - 1.0) > 1e-2) {
      throw InputError(file.string() + ":" + std::to_string(line_no) +
                       ": quaternion is not unit-norm (norm " + std::to_string(n) + ")");
    }
    if (!out.empty() && v[0] < out.back().stamp) {
      throw InputError(file.string() + ":" + std::to_string(line_no) + ": timestamp " +
                       std::to_string(v[0]) + " is before the previous one");
    }
    if (!out.empty() && v[0] == out.back().stamp) {
      // The real fr3/walking_static ground truth repeats one stamp with poses 0.5 mm apart: the
      // first is kept (the rendered sequences depend on it). Two poses further apart under one
      // stamp are two different claims about the camera, and neither can be chosen.
      const Eigen::Isometry3d& kept = out.back().pose;
      const double apart = (kept.translation() - Eigen::Vector3d(v[1], v[2], v[3])).norm();
      const double angle =
          Eigen::AngleAxisd(kept.linear().transpose() * q.normalized().toRotationMatrix()).angle();
      if (apart > 0.01 || angle > 1.0 * M_PI / 180.0) {
        throw InputError(file.string() + ":" + std::to_string(line_no) + ": timestamp " +
                         std::to_string(v[0]) + " repeats with a pose " +
                         std::to_string(apart * 100.0) + " cm and " +
                         std::to_string(angle * 180.0 / M_PI) +
                         " deg from the earlier one (more than 1 cm or 1 deg apart)");
      }
      continue;
    }
    StampedPose p;
    p.stamp = v[0];
    p.pose.linear() = q.normalized().toRotationMatrix();
    p.pose.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    out.push_back(p);
  }
  if (out.size() < 2) throw InputError(file.string() + ": fewer than two poses");
  return out;
}

std::vector<StampedPose> resample(const std::vector<StampedPose>& gt, double rate, int max_frames) {
  std::vector<StampedPose> out;
  const double t0 = gt.front().stamp;
  const double t_end = gt.back().stamp;
  std::size_t k = 0;
  for (long i = 0;; ++i) {
    if (max_frames > 0 && i >= max_frames) break;
    // Stamps from an integer index, never by accumulation, so frame i's stamp is exact.
    const double t = t0 + static_cast<double>(i) / rate;
    if (t > t_end) break;
    while (k + 2 < gt.size() && gt[k + 1].stamp < t) ++k;
    const StampedPose& a = gt[k];
    const StampedPose& b = gt[k + 1];
    const double s = std::clamp((t - a.stamp) / (b.stamp - a.stamp), 0.0, 1.0);
    const Eigen::Quaterniond qa(a.pose.linear());
    const Eigen::Quaterniond qb(b.pose.linear());
    StampedPose p;
    p.stamp = t;
    p.pose.linear() = qa.slerp(s, qb).normalized().toRotationMatrix();
    p.pose.translation() = (1.0 - s) * a.pose.translation() + s * b.pose.translation();
    out.push_back(p);
  }
  return out;
}

Pose room_offset(const std::vector<StampedPose>& path, const Eigen::Vector2d& camera_xy) {
  // Least-squares meeting point of the optical axes: sum_i (I - d d^T)(p - c_i) = 0, regularised
  // towards 2 m ahead of the mean camera (parallel axes, as in walking_xyz, leave it undefined).
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean_c = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean_d = Eigen::Vector3d::Zero();
  for (const auto& p : path) {
    const Eigen::Vector3d c = p.pose.translation();
    const Eigen::Vector3d d = p.pose.linear().col(2);
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d * d.transpose();
    A += P;
    b += P * c;
    mean_c += c;
    mean_d += d;
  }
  const double n = static_cast<double>(path.size());
  mean_c /= n;
  mean_d.normalize();
  const Eigen::Vector3d prior = mean_c + 2.0 * mean_d;
  const double lambda = 0.05 * n;
  const Eigen::Vector3d look =
      (A + lambda * Eigen::Matrix3d::Identity()).ldlt().solve(b + lambda * prior);
  Eigen::Vector2d dir(look.x() - mean_c.x(), look.y() - mean_c.y());
  if (dir.norm() < 1e-6) dir = Eigen::Vector2d(mean_d.x(), mean_d.y());
  dir.normalize();
  // Yaw that turns `dir` onto +y.
  const double yaw = std::atan2(dir.x(), dir.y());
  Pose T = Pose::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d c_rot = T.linear() * Eigen::Vector3d(mean_c.x(), mean_c.y(), 0.0);
  T.translation() = Eigen::Vector3d(camera_xy.x() - c_rot.x(), camera_xy.y() - c_rot.y(), 0.0);
  return T;
}

}  // namespace hbos::render
