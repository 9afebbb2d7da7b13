#pragma once
/// \file
/// A small Gauss-Newton refinement of a camera pose from 3D-2D matches, for the iterated
/// screen -> refit -> re-screen mode (and for tests). It is not a replacement for g2o/Ceres in a
/// SLAM back end: it refines one pose, from a good start, on the matches a screen kept.
///
/// Cost (whitened reprojection error, as ORB-SLAM2's PoseOptimization):
///
///     E(T) = sum_{i kept} rho( |pi(T * X_i) - z_i|^2 / sigma_i^2 )
///
/// with rho the Huber loss of width `huber_delta` (identity when 0), minimised by Gauss-Newton on
/// the left perturbation T <- exp(delta) * T, delta = (omega, tau) in R^6. The Jacobian of
/// p = T X is [-[p]x, I]; that of the pinhole projection is
/// [[fx/z, 0, -fx x/z^2], [0, fy/z, -fy y/z^2]].
///
/// Threading: re-entrant; allocation-free (fixed-size matrices only).

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "hbos/error.hpp"
#include "hbos/screening/pinhole.hpp"

namespace hbos {

/// Gauss-Newton settings.
struct PoseRefinementOptions {
  int max_iterations = 10;  ///< Gauss-Newton steps, >= 1 (ORB-SLAM2 uses 10 per round)
  double huber_delta =
      2.447;  ///< [px/sigma] Huber width on the whitened error; 0 = plain least squares
  double min_depth = 1e-3;  ///< [m] points closer than this (or behind the camera) are skipped
  double step_tolerance = 1e-10;  ///< stop when |delta| falls below this [rad, m]
};

/// What refine_pose did.
struct PoseRefinementSummary {
  int iterations = 0;       ///< Gauss-Newton steps taken
  Eigen::Index used = 0;    ///< matches that entered the last step
  double initial_cost = 0;  ///< E at the start [px^2/sigma^2, Huber-weighted]
  double final_cost = 0;    ///< E at the end
  bool converged = false;   ///< the last step was below step_tolerance
};

namespace detail {

template <class Scalar>
Eigen::Matrix<Scalar, 3, 3> so3_exp(const Eigen::Matrix<Scalar, 3, 1>& omega) {
  const Scalar angle = omega.norm();
  if (angle < Scalar(1e-12)) {
    Eigen::Matrix<Scalar, 3, 3> R = Eigen::Matrix<Scalar, 3, 3>::Identity();
    R(0, 1) = -omega.z();
    R(0, 2) = omega.y();
    R(1, 0) = omega.z();
    R(1, 2) = -omega.x();
    R(2, 0) = -omega.y();
    R(2, 1) = omega.x();
    return R;
  }
  return Eigen::AngleAxis<Scalar>(angle, omega / angle).toRotationMatrix();
}

/// Jacobian of the pixel pi(p) w.r.t. the left perturbation delta = (omega, tau) of the pose that
/// produced p = T X (T <- exp(delta) * T), not whitened: the pinhole's
/// [[fx/z, 0, -fx x/z^2], [0, fy/z, -fy y/z^2]] times [-[p]x, I]. `inv_z` is 1 / p.z(), which
/// the caller has already computed for the projection itself. Shared by refine_pose and
/// group_leverage (pose_leverage.hpp), so both see the same information.
template <class Scalar>
Eigen::Matrix<Scalar, 2, 6> projection_jacobian(const PinholeCamera<Scalar>& camera,
                                                const Eigen::Matrix<Scalar, 3, 1>& p,
                                                Scalar inv_z) {
  Eigen::Matrix<Scalar, 2, 3> J_proj;
  J_proj << camera.fx * inv_z, 0, -camera.fx * p.x() * inv_z * inv_z, 0, camera.fy * inv_z,
      -camera.fy * p.y() * inv_z * inv_z;
  Eigen::Matrix<Scalar, 3, 6> J_pose;
  J_pose << 0, p.z(), -p.y(), 1, 0, 0,  //
      -p.z(), 0, p.x(), 0, 1, 0,        //
      p.y(), -p.x(), 0, 0, 0, 1;
  return J_proj * J_pose;
}

inline void validate(const PoseRefinementOptions& o) {
  require(o.max_iterations >= 1, "PoseRefinementOptions max_iterations must be >= 1, got ",
          o.max_iterations);
  require(o.huber_delta >= 0.0 && std::isfinite(o.huber_delta),
          "PoseRefinementOptions huber_delta must be finite and >= 0, got ", o.huber_delta);
  require(o.min_depth > 0.0 && std::isfinite(o.min_depth),
          "PoseRefinementOptions min_depth must be finite and > 0, got ", o.min_depth);
  require(o.step_tolerance >= 0.0, "PoseRefinementOptions step_tolerance must be >= 0, got ",
          o.step_tolerance);
}

}  // namespace detail

/// Refines `T_cur_world` in place from n matches: map points `point(i)` (world frame [m]),
/// observed pixels `observed(i)` [px], scale sigmas `sigma(i)`, using only those with `use(i)`.
/// The accessors are callables so that any storage plugs in without copies.
/// Fewer than 3 usable matches leave the pose unchanged (summary.iterations == 0).
/// \throws InvalidArgument on invalid options or intrinsics.
template <class Scalar, class Point, class Observed, class Sigma, class Use>
PoseRefinementSummary refine_pose(Eigen::Index n, const Point& point, const Observed& observed,
                                  const Sigma& sigma, const Use& use,
                                  const PinholeCamera<Scalar>& camera,
                                  Eigen::Transform<Scalar, 3, Eigen::Isometry>& T_cur_world,
                                  const PoseRefinementOptions& options = {}) {
  detail::validate(options);
  detail::validate(camera);
  using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
  using Vec6 = Eigen::Matrix<Scalar, 6, 1>;
  using Mat6 = Eigen::Matrix<Scalar, 6, 6>;
  const auto delta = static_cast<Scalar>(options.huber_delta);
  const auto min_depth = static_cast<Scalar>(options.min_depth);

  PoseRefinementSummary summary;
  // One pass: the normal equations at the current pose, and its cost.
  auto linearise = [&](Mat6& H, Vec6& b, Eigen::Index& used) {
    H.setZero();
    b.setZero();
    used = 0;
    Scalar cost = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!use(i)) continue;
      const Vec3 p = T_cur_world * Vec3(point(i));
      if (!(p.z() > min_depth)) continue;
      const Scalar inv_z = Scalar(1) / p.z();
      const Eigen::Matrix<Scalar, 2, 1> uv(camera.fx * p.x() * inv_z + camera.cx,
                                           camera.fy * p.y() * inv_z + camera.cy);
      const Eigen::Matrix<Scalar, 2, 1> e = uv - Eigen::Matrix<Scalar, 2, 1>(observed(i));
      const Scalar s = static_cast<Scalar>(sigma(i));
      const Scalar info = Scalar(1) / (s * s);
      const Scalar chi2 = e.squaredNorm() * info;
      // Huber: weight 1 inside delta, delta/|e| outside (IRLS form of the Huber loss).
      Scalar w = Scalar(1);
      if (delta > Scalar(0)) {
        const Scalar norm = std::sqrt(chi2);
        if (norm > delta) w = delta / norm;
        cost += norm > delta ? Scalar(2) * delta * norm - delta * delta : chi2;
      } else {
        cost += chi2;
      }
      const Eigen::Matrix<Scalar, 2, 6> J = detail::projection_jacobian(camera, p, inv_z);
      H.noalias() += (w * info) * J.transpose() * J;
      b.noalias() -= (w * info) * J.transpose() * e;
      ++used;
    }
    return cost;
  };

  Mat6 H;
  Vec6 b;
  Eigen::Index used = 0;
  Scalar cost = linearise(H, b, used);
  summary.initial_cost = static_cast<double>(cost);
  summary.final_cost = summary.initial_cost;
  summary.used = used;
  if (used < 3) return summary;
  for (int it = 0; it < options.max_iterations; ++it) {
    const Vec6 step = H.ldlt().solve(b);
    if (!step.allFinite()) break;
    Eigen::Transform<Scalar, 3, Eigen::Isometry> update =
        Eigen::Transform<Scalar, 3, Eigen::Isometry>::Identity();
    update.linear() = detail::so3_exp<Scalar>(step.template head<3>());
    update.translation() = step.template tail<3>();
    const Eigen::Transform<Scalar, 3, Eigen::Isometry> previous = T_cur_world;
    T_cur_world = update * T_cur_world;
    const Scalar new_cost = linearise(H, b, used);
    ++summary.iterations;
    if (!(new_cost <= cost) || used < 3) {
      // A step that does not lower the cost is undone (Gauss-Newton without damping).
      T_cur_world = previous;
      break;
    }
    cost = new_cost;
    summary.used = used;
    if (static_cast<double>(step.norm()) < options.step_tolerance) {
      summary.converged = true;
      break;
    }
  }
  summary.final_cost = static_cast<double>(cost);
  return summary;
}

}  // namespace hbos
