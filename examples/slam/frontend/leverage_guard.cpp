#include "frontend/leverage_guard.hpp"

#include "frontend/shared_bias.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>
#include <hbos/screening/noise_scale.hpp>
#include <hbos/screening/pose_leverage.hpp>

#include <Eigen/Cholesky>

#include <cmath>
#include <cstddef>

namespace hbos::slam {

namespace {

/// The chi-square quantile with 2 degrees of freedom at the one-sided normal quantile z: the
/// tail probability p = erfc(z / sqrt 2) / 2, and -2 ln p (exact for 2 degrees of freedom).
double chi_square_2_quantile(double z) {
  return -2.0 * std::log(0.5 * std::erfc(z / std::sqrt(2.0)));
}

}  // namespace

LeverageGuard::LeverageGuard(const LeverageGuardConfig& config) : config_(config) {
  const auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!positive(config_.radius_px) || !positive(config_.max_ratio) ||
      !positive(config_.consistency_z)) {
    throw InvalidArgument(
        fmt::format("leverage guard settings: radius {} px, ratio limit {} and consistency z {} "
                    "must be finite and > 0",
                    config_.radius_px, config_.max_ratio, config_.consistency_z));
  }
  if (!(std::isfinite(config_.bias_cell_px) && config_.bias_cell_px >= 0.0)) {
    throw InvalidArgument(fmt::format(
        "leverage guard settings: shared-bias cell {} px must be finite and >= 0 (0: none)",
        config_.bias_cell_px));
  }
}

double LeverageGuard::reach_px(MaskSource mask_source) const {
  return config_.enabled && mask_source != MaskSource::kNone ? config_.radius_px : 0.0;
}

GuardOutcome LeverageGuard::apply(const std::vector<Eigen::Vector3d>& points,
                                  const std::vector<Eigen::Vector2d>& observed,
                                  const std::vector<double>& sigma,
                                  const std::vector<double>& mask_distance_px,
                                  const Eigen::Isometry3d& T_cur_prev, const PoseRefiner& refiner,
                                  std::vector<std::uint8_t>& inlier) const {
  GuardOutcome out;
  if (!config_.enabled || mask_distance_px.empty()) return out;
  const std::size_t n = inlier.size();
  if (points.size() != n || observed.size() != n || sigma.size() != n ||
      mask_distance_px.size() != n)
    throw InvalidArgument(fmt::format(
        "leverage guard: {} points, {} observations, {} sigmas and {} mask distances for {} "
        "screened matches",
        points.size(), observed.size(), sigma.size(), mask_distance_px.size(), n));
  const hbos::PinholeCamerad& camera = refiner.camera();
  const auto at = [](Eigen::Index i) { return static_cast<std::size_t>(i); };
  const auto near = [&](std::size_t i) { return mask_distance_px[i] <= config_.radius_px; };

  // 1. Is a direction of the pose decided by the group alone?
  const hbos::GroupLeverage leverage = hbos::group_leverage(
      static_cast<Eigen::Index>(n), [&](Eigen::Index i) { return points[at(i)]; },
      [&](Eigen::Index i) { return sigma[at(i)]; },
      [&](Eigen::Index i) { return inlier[at(i)] != 0; },
      [&](Eigen::Index i) { return near(at(i)); }, camera, T_cur_prev);
  if (leverage.group == 0) return out;
  out.ratio = leverage.ratio;
  // +inf: the others cannot fix a pose without the group; there is nothing to trust instead.
  if (!(leverage.ratio > config_.max_ratio) || !std::isfinite(leverage.ratio)) return out;

  // 2. Does the group disagree with the pose the others give on their own?
  std::vector<std::uint8_t> rest(n, 0);
  for (std::size_t i = 0; i < n; ++i) rest[i] = inlier[i] != 0 && !near(i) ? 1 : 0;
  Eigen::Isometry3d T_rest = T_cur_prev;
  refiner.refine(points, observed, sigma, rest, T_rest);
  // The noise the others show, in sigma units: the Rayleigh scale of their whitened residuals
  // read at the median (the screen's own estimator, hbos/screening/noise_scale.hpp), so a frame
  // noisier than the octave model does not count against the group.
  std::vector<double> rest_residual;
  std::vector<Eigen::Vector2d> rest_pixel, rest_vector;
  for (std::size_t i = 0; i < n; ++i) {
    if (rest[i] == 0) continue;
    const Eigen::Vector3d p = T_rest * points[i];
    if (!(p.z() > 0.0)) continue;
    const Eigen::Vector2d r = (camera.project(p) - observed[i]) / sigma[i];
    rest_residual.push_back(r.norm());
    rest_pixel.push_back(observed[i]);
    rest_vector.push_back(r);
  }
  if (rest_residual.empty()) return out;
  const double noise = hbos::detail::rayleigh_scale(rest_residual, rest_residual.size(), 0.5);
  if (!(noise > 0.0)) return out;
  // The offset the others' neighbourhoods share in this frame.
  out.shared_bias = config_.bias_cell_px > 0.0
                        ? shared_bias_scales(rest_pixel, rest_vector, noise, config_.bias_cell_px)
                        : 0.0;
  const hbos::GroupConsistency consistency = hbos::group_consistency(
      static_cast<Eigen::Index>(n), [&](Eigen::Index i) { return points[at(i)]; },
      [&](Eigen::Index i) { return observed[at(i)]; }, [&](Eigen::Index i) { return sigma[at(i)]; },
      [&](Eigen::Index i) { return inlier[at(i)] != 0; },
      [&](Eigen::Index i) { return near(at(i)); }, camera, T_rest, noise);
  if (consistency.dof == 0) return out;
  // The group's common shift: a person's rim moves together. Static neighbours share a small
  // offset too, which no number of them averages away: its variance joins the shift's.
  const double bias = out.shared_bias * noise;
  const Eigen::Matrix2d C =
      consistency.shift_covariance + bias * bias * Eigen::Matrix2d::Identity();
  const Eigen::LLT<Eigen::Matrix2d> C_llt(C);
  if (C_llt.info() != Eigen::Success) return out;
  const double shift_chi2 = consistency.mean_residual.dot(C_llt.solve(consistency.mean_residual));
  out.disagreement = shift_chi2 / chi_square_2_quantile(config_.consistency_z);
  out.shift_scales = consistency.mean_residual.norm() / noise;
  if (!(out.disagreement > 1.0)) return out;
  for (std::size_t i = 0; i < n; ++i) {
    if (inlier[i] != 0 && near(i)) {
      inlier[i] = 0;
      ++out.dropped;
    }
  }
  return out;
}

}  // namespace hbos::slam
