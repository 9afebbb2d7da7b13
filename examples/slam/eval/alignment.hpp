#pragma once
/// \file
/// Least-squares alignment of two corresponding point sets: rigid (Horn / Kabsch, as TUM's
/// evaluate_ate.py) and similarity (Umeyama 1991, for scale-free monocular trajectories).

#include <Eigen/Core>

namespace hbos::slam {

/// A similarity transform y = scale · rotation · x + translation. Maps estimate positions into
/// the ground-truth frame (`T_gt_est`); scale is exactly 1 for a rigid alignment.
struct Similarity3 {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< proper rotation, det = +1
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();   ///< [m] in the ground-truth frame
  double scale = 1.0;                                      ///< [-]

  /// Applies the transform to every column.
  [[nodiscard]] Eigen::Matrix3Xd apply(const Eigen::Matrix3Xd& points) const;
};

/// Rigid alignment minimising Σ‖R x_i + t − y_i‖² over proper rotations R (Horn 1987 / Kabsch),
/// computed as evaluate_ate.py's align(model = x, data = y):
///   W = Σ (x_i − x̄)(y_i − ȳ)ᵀ;  U Σ Vᵀ = svd(Wᵀ);  S = diag(1, 1, −1) if det U · det V < 0;
///   R = U S Vᵀ;  t = ȳ − R x̄.
/// Without S a mirrored point set would get a reflection (det R = −1); with it, R is the best
/// proper rotation (Umeyama 1991, eq. 39–43).
/// Throws hbos::InvalidArgument unless x and y have the same number (>= 2) of finite columns.
[[nodiscard]] Similarity3 align_rigid(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& y);

/// Similarity alignment minimising Σ‖c R x_i + t − y_i‖² (Umeyama 1991, eq. 40–42):
///   σx² = (1/n) Σ‖x_i − x̄‖²;  Σxy = (1/n) Σ (y_i − ȳ)(x_i − x̄)ᵀ = U D Vᵀ;
///   S as above;  R = U S Vᵀ;  c = tr(D S) / σx²;  t = ȳ − c R x̄.
/// R equals align_rigid's rotation. Throws hbos::InvalidArgument as align_rigid, and when all
/// x_i coincide (σx² = 0: no scale can be estimated).
[[nodiscard]] Similarity3 align_similarity(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& y);

}  // namespace hbos::slam
