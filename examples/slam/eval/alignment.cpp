#include "eval/alignment.hpp"

#include <hbos/error.hpp>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace hbos::slam {

namespace {

void check_point_sets(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& y, const char* who) {
  detail::require(x.cols() == y.cols(), who, ": point sets differ in size: ", x.cols(), " vs ",
                  y.cols());
  detail::require(x.cols() >= 2, who, ": needs at least 2 corresponding points, got ", x.cols());
  detail::require(x.allFinite() && y.allFinite(), who, ": points must be finite");
}

// The rotation of Umeyama's eq. 39–43 from the SVD of the cross-covariance M = Σ y xᵀ (up to a
// positive factor): R = U S Vᵀ with S flipping the last axis when U Vᵀ would be a reflection.
// Also returns tr(D S), needed for the scale.
Eigen::Matrix3d proper_rotation(const Eigen::Matrix3d& m, double* trace_ds) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d s = Eigen::Vector3d::Ones();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) s(2) = -1.0;
  if (trace_ds != nullptr) *trace_ds = svd.singularValues().dot(s);
  return svd.matrixU() * s.asDiagonal() * svd.matrixV().transpose();
}

}  // namespace

Eigen::Matrix3Xd Similarity3::apply(const Eigen::Matrix3Xd& points) const {
  return ((scale * rotation) * points).colwise() + translation;
}

Similarity3 align_rigid(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& y) {
  check_point_sets(x, y, "align_rigid");
  const Eigen::Vector3d x_mean = x.rowwise().mean();
  const Eigen::Vector3d y_mean = y.rowwise().mean();
  // evaluate_ate.py decomposes Wᵀ = Σ (y_i − ȳ)(x_i − x̄)ᵀ.
  const Eigen::Matrix3d w_t = (y.colwise() - y_mean) * (x.colwise() - x_mean).transpose();
  Similarity3 result;
  result.rotation = proper_rotation(w_t, nullptr);
  result.translation = y_mean - result.rotation * x_mean;
  return result;
}

Similarity3 align_similarity(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& y) {
  check_point_sets(x, y, "align_similarity");
  const auto n = static_cast<double>(x.cols());
  const Eigen::Vector3d x_mean = x.rowwise().mean();
  const Eigen::Vector3d y_mean = y.rowwise().mean();
  const Eigen::Matrix3Xd x_centred = x.colwise() - x_mean;
  const double x_variance = x_centred.squaredNorm() / n;
  const Eigen::Matrix3Xd y_centred = y.colwise() - y_mean;
  // A spread at the level of the coordinates' rounding is no spread: points that coincide but for
  // their last bits gave a scale of 1e-28 and a "perfect" fit. 1e-9 of the coordinates' size
  // (a nanometre at a metre from the origin) is millions of roundings, and far below any motion
  // a trajectory measures.
  const auto spread_is_rounding = [](double variance, const Eigen::Vector3d& mean) {
    return !(std::sqrt(variance) > 1e-9 * std::max(1.0, mean.norm()));
  };
  detail::require(!spread_is_rounding(x_variance, x_mean),
                  "align_similarity: all estimate points coincide, so no scale can be estimated");
  detail::require(!spread_is_rounding(y_centred.squaredNorm() / n, y_mean),
                  "align_similarity: all ground-truth points coincide, so no scale can be "
                  "estimated");
  const Eigen::Matrix3d sigma_xy = y_centred * x_centred.transpose() / n;
  double trace_ds = 0.0;
  Similarity3 result;
  result.rotation = proper_rotation(sigma_xy, &trace_ds);
  result.scale = trace_ds / x_variance;
  result.translation = y_mean - result.scale * (result.rotation * x_mean);
  return result;
}

}  // namespace hbos::slam
