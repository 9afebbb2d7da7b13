#pragma once
/// \file
/// How decisive a group of matches is for a camera pose: whether some direction of the pose is
/// fixed by the group rather than by all other matches together.
///
/// Why it matters. In a frame whose static matches are all far away, a small rotation and a
/// suitable small translation move them alike on the image, so the pose along that combined
/// direction is weakly constrained. A handful of near matches - for instance a person's rim just
/// outside a segmentation mask, which the mask did not cover - then decides that direction alone,
/// and if they move, the pose follows them however few they are.
///
/// What is measured. With H_group and H_rest the Gauss-Newton information of the pose (the
/// J^T J / sigma^2 of refine_pose, without robust weights) from the group's matches and from all
/// other matches, the leverage is the largest generalised eigenvalue
///
///     ratio = max_v (v^T H_group v) / (v^T H_rest v),
///
/// i.e. the largest eigenvalue of L^-1 H_group L^-T with H_rest = L L^T. ratio > 1 means: along
/// some direction of the pose, the group alone carries more information than all other matches
/// together. A change of basis of the pose (H -> A^T H A for both) leaves the generalised
/// eigenvalues unchanged, so the ratio does not depend on the units of rotation and translation:
/// no weighting of radians against metres enters.
///
/// Whether a decisive group is wrong is a second question, answered by group_consistency: the
/// group's residuals under the pose the other matches give on their own, tested against the
/// noise and against that pose's own uncertainty (which a decisive group's direction makes
/// large).
///
/// Threading: re-entrant; allocation-free (fixed-size matrices only).

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "hbos/error.hpp"
#include "hbos/screening/pinhole.hpp"
#include "hbos/screening/pose_refinement.hpp"

namespace hbos {

/// What group_leverage measured.
struct GroupLeverage {
  /// Largest generalised eigenvalue lambda of H_group v = lambda H_rest v; +inf when the rest's
  /// information is not positive definite (and the group is non-empty); 0 for an empty group;
  /// NaN when the information is not finite (a point at infinite depth, or one so far off the
  /// axis that its information overflows; a NaN point fails the depth test and is skipped).
  double ratio = 0.0;
  Eigen::Index group = 0;  ///< usable matches in the group
  Eigen::Index rest = 0;   ///< usable matches outside it
};

/// The leverage of the matches with `in_group(i)` on the pose `T_cur_world`, among n matches: map
/// points `point(i)` (world frame [m]) and scale sigmas `sigma(i)` [px], using only those with
/// `use(i)` whose point lies deeper than `min_depth` [m] in the camera (as refine_pose skips the
/// others). The accessors are callables, as refine_pose's. The information is accumulated in
/// double whatever Scalar is: the case this exists for, a far background, makes H_rest
/// ill-conditioned, and a float sum would blur the very direction that is weakly constrained.
/// Fewer than 3 usable matches outside the group cannot fix the 6 degrees of freedom of a pose
/// (each gives 2 rows): the ratio is then +inf for a non-empty group.
/// \throws InvalidArgument on invalid intrinsics, min_depth, or the sigma of a usable match.
template <class Scalar, class Point, class Sigma, class Use, class InGroup>
GroupLeverage group_leverage(Eigen::Index n, const Point& point, const Sigma& sigma, const Use& use,
                             const InGroup& in_group, const PinholeCamera<Scalar>& camera,
                             const Eigen::Transform<Scalar, 3, Eigen::Isometry>& T_cur_world,
                             double min_depth = 1e-3) {
  detail::validate(camera);
  detail::require(std::isfinite(min_depth) && min_depth > 0.0,
                  "group_leverage min_depth must be finite and > 0, got ", min_depth);
  using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
  using Mat6d = Eigen::Matrix<double, 6, 6>;
  // The same depth test as refine_pose, in Scalar, so both skip the same matches.
  const auto min_z = static_cast<Scalar>(min_depth);

  GroupLeverage result;
  Mat6d H_group = Mat6d::Zero();
  Mat6d H_rest = Mat6d::Zero();
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!use(i)) continue;
    const Vec3 p = T_cur_world * Vec3(point(i));
    if (!(p.z() > min_z)) continue;
    const auto s = static_cast<double>(sigma(i));
    detail::require(std::isfinite(s) && s > 0.0, "group_leverage sigma(", i,
                    ") must be finite and > 0, got ", s);
    const Eigen::Matrix<double, 2, 6> J =
        detail::projection_jacobian(camera, p, Scalar(1) / p.z()).template cast<double>();
    const double info = 1.0 / (s * s);
    if (in_group(i)) {
      H_group.noalias() += info * J.transpose() * J;
      ++result.group;
    } else {
      H_rest.noalias() += info * J.transpose() * J;
      ++result.rest;
    }
  }
  if (result.group == 0) return result;
  if (!H_group.allFinite() || !H_rest.allFinite()) {
    result.ratio = std::numeric_limits<double>::quiet_NaN();
    return result;
  }

  const Eigen::LLT<Mat6d> llt(H_rest);
  // Fewer than 3 matches leave H_rest singular in exact arithmetic, but rounding can still let
  // the factorisation through with a tiny pivot; the count decides, not the rounding.
  if (result.rest < 3 || llt.info() != Eigen::Success) {
    result.ratio = std::numeric_limits<double>::infinity();
    return result;
  }
  // A = L^-1 H_group L^-T, symmetric; its eigenvalues are the generalised ones.
  const Mat6d left = llt.matrixL().solve(H_group);
  Mat6d A = llt.matrixL().solve(left.transpose());
  A = (0.5 * (A + A.transpose())).eval();
  const Eigen::SelfAdjointEigenSolver<Mat6d> eigen(A, Eigen::EigenvaluesOnly);
  if (eigen.info() != Eigen::Success) {  // not seen with finite input; never pass it off as 0
    result.ratio = std::numeric_limits<double>::quiet_NaN();
    return result;
  }
  // Both informations are positive semi-definite, so a negative value is only rounding.
  const double largest = eigen.eigenvalues().maxCoeff();
  result.ratio = largest < 0.0 ? 0.0 : largest;
  return result;
}

/// What group_consistency measured.
struct GroupConsistency {
  /// All of the group's residuals against "static" (below); NaN when it cannot be formed (no
  /// usable group match, fewer than 3 usable matches outside it, or information that is not
  /// positive definite or not finite).
  double chi2 = std::numeric_limits<double>::quiet_NaN();
  Eigen::Index dof = 0;  ///< 2 per usable group match: chi2's degrees of freedom if static
  /// The group's mean residual against "static": chi-square with 2 degrees of freedom if
  /// static. A group that moves together (a person's rim) concentrates its evidence here, where
  /// `chi2` spreads it over `dof`. NaN as chi2.
  double shift_chi2 = std::numeric_limits<double>::quiet_NaN();
  /// The group's mean whitened residual under T_rest [sigma units] and its covariance C if the
  /// group is static [sigma^2 units]: shift_chi2 = mean_residual^T C^-1 mean_residual. C's
  /// noise part shrinks as 1 / k, so a large enough group makes any shared offset significant;
  /// a caller whose static neighbourhoods share a small bias (real depth and timing errors do)
  /// can add its variance to C and test again. NaN as chi2.
  Eigen::Vector2d mean_residual =
      Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Matrix2d shift_covariance =
      Eigen::Matrix2d::Constant(std::numeric_limits<double>::quiet_NaN());
};

/// Tests whether the matches with `in_group(i)` agree with the others, given `T_rest`: the pose
/// fitted (least squares, e.g. refine_pose) to the usable matches outside the group alone.
///
/// If the group were static, its whitened residuals r_i under T_rest would be its noise plus the
/// rest's pose error delta ~ N(0, s^2 H_rest^-1) seen through each match's whitened Jacobian
/// J_i, with s = `noise_scale` in sigma units. Two statistics, both chi-square if static:
///
///     chi2       = (r_G^T r_G - g^T (H_rest + H_group)^-1 g) / s^2,   g = J_G^T r_G
///                  (r_G's Mahalanobis norm under s^2 (I + J_G H_rest^-1 J_G^T), by Woodbury;
///                  2 per match degrees of freedom),
///     shift_chi2 = mean(r)^T C^-1 mean(r),   C = s^2 (I / k + mean(J) H_rest^-1 mean(J)^T)
///                  (the group's mean residual over its k matches; 2 degrees of freedom).
///
/// Both count the rest's own pose uncertainty, which is large along the direction a decisive
/// group decides. Accessors as group_leverage's, plus `observed(i)` [px].
/// \throws InvalidArgument on invalid intrinsics, min_depth, noise_scale, or the sigma of a
/// usable match.
template <class Scalar, class Point, class Observed, class Sigma, class Use, class InGroup>
GroupConsistency group_consistency(Eigen::Index n, const Point& point, const Observed& observed,
                                   const Sigma& sigma, const Use& use, const InGroup& in_group,
                                   const PinholeCamera<Scalar>& camera,
                                   const Eigen::Transform<Scalar, 3, Eigen::Isometry>& T_rest,
                                   double noise_scale = 1.0, double min_depth = 1e-3) {
  detail::validate(camera);
  detail::require(std::isfinite(min_depth) && min_depth > 0.0,
                  "group_consistency min_depth must be finite and > 0, got ", min_depth);
  detail::require(std::isfinite(noise_scale) && noise_scale > 0.0,
                  "group_consistency noise_scale must be finite and > 0, got ", noise_scale);
  using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
  using Mat6d = Eigen::Matrix<double, 6, 6>;
  using Vec6d = Eigen::Matrix<double, 6, 1>;
  const auto min_z = static_cast<Scalar>(min_depth);

  GroupConsistency result;
  Mat6d H_rest = Mat6d::Zero();
  Mat6d H_group = Mat6d::Zero();
  Vec6d g = Vec6d::Zero();
  Eigen::Matrix<double, 2, 6> J_sum = Eigen::Matrix<double, 2, 6>::Zero();
  Eigen::Vector2d r_sum = Eigen::Vector2d::Zero();
  double r2 = 0.0;
  Eigen::Index n_rest = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!use(i)) continue;
    const Vec3 p = T_rest * Vec3(point(i));
    if (!(p.z() > min_z)) continue;
    const auto s = static_cast<double>(sigma(i));
    detail::require(std::isfinite(s) && s > 0.0, "group_consistency sigma(", i,
                    ") must be finite and > 0, got ", s);
    const Scalar inv_z = Scalar(1) / p.z();
    // Whitened Jacobian and residual: both divided by sigma.
    const Eigen::Matrix<double, 2, 6> J =
        detail::projection_jacobian(camera, p, inv_z).template cast<double>() / s;
    if (!in_group(i)) {
      H_rest.noalias() += J.transpose() * J;
      ++n_rest;
      continue;
    }
    const Eigen::Matrix<Scalar, 2, 1> uv(camera.fx * p.x() * inv_z + camera.cx,
                                         camera.fy * p.y() * inv_z + camera.cy);
    const Eigen::Vector2d r =
        (uv - Eigen::Matrix<Scalar, 2, 1>(observed(i))).template cast<double>() / s;
    H_group.noalias() += J.transpose() * J;
    r2 += r.squaredNorm();
    g.noalias() += J.transpose() * r;
    J_sum += J;
    r_sum += r;
    result.dof += 2;
  }
  // Fewer than 3 rest matches cannot fix a pose (as in group_leverage, the count decides: a
  // singular H_rest can pass the factorisation by rounding).
  if (result.dof == 0 || n_rest < 3 || !H_rest.allFinite() || !H_group.allFinite() ||
      !g.allFinite() || !std::isfinite(r2))
    return result;
  const double s2 = noise_scale * noise_scale;
  const Eigen::LLT<Mat6d> all(H_rest + H_group);
  const Eigen::LLT<Mat6d> rest(H_rest);
  if (all.info() != Eigen::Success || rest.info() != Eigen::Success) return result;
  // The subtracted part is at most r2 in exact arithmetic; rounding must not make chi2 < 0.
  result.chi2 = std::max(0.0, r2 - g.dot(all.solve(g))) / s2;
  const double k = static_cast<double>(result.dof) / 2.0;  // dof is even: exact
  const Eigen::Vector2d mean_r = r_sum / k;
  const Eigen::Matrix<double, 2, 6> mean_J = J_sum / k;
  const Eigen::Matrix2d C =
      s2 * (Eigen::Matrix2d::Identity() / k + mean_J * rest.solve(mean_J.transpose()));
  result.shift_chi2 = mean_r.dot(C.llt().solve(mean_r));
  result.mean_residual = mean_r;
  result.shift_covariance = C;
  return result;
}

}  // namespace hbos
