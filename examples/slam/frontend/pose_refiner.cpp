#include "frontend/pose_refiner.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>
#include <hbos/screening/noise_scale.hpp>
#include <hbos/screening/pose_refinement.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace hbos::slam {

namespace {

// Fewer refined matches than this leave the width at ORB-SLAM2's: a median of a handful of
// residuals is not a noise scale.
constexpr std::size_t kMinMatchesForNoise = 10;

}  // namespace

PoseRefiner::PoseRefiner(const RefinementConfig& config, hbos::PinholeCamerad camera)
    : config_(config), camera_(camera) {
  if (config_.max_iterations < 1 || !(config_.huber_delta >= 0.0) ||
      !std::isfinite(config_.huber_delta)) {
    throw InvalidArgument(fmt::format(
        "refinement settings: iterations {} must be >= 1, Huber width {} finite and >= 0",
        config_.max_iterations, config_.huber_delta));
  }
  if (!(config_.min_noise_scale > 0.0 && config_.min_noise_scale <= 1.0)) {
    throw InvalidArgument(
        fmt::format("refinement settings: the smallest noise scale {} must lie in (0, 1]",
                    config_.min_noise_scale));
  }
}

double PoseRefiner::huber_width(const std::vector<Eigen::Vector3d>& points_prev,
                                const std::vector<Eigen::Vector2d>& observed,
                                const std::vector<double>& sigma,
                                const std::vector<std::uint8_t>& use,
                                const Eigen::Isometry3d& T_cur_prev) const {
  if (!config_.huber_from_noise || config_.huber_delta == 0.0) return config_.huber_delta;
  const double min_depth = hbos::PoseRefinementOptions{}.min_depth;  // as refine() skips them
  std::vector<double> whitened;
  whitened.reserve(points_prev.size());
  for (std::size_t i = 0; i < points_prev.size(); ++i) {
    if (use[i] == 0) continue;
    const Eigen::Vector3d p = T_cur_prev * points_prev[i];
    if (!(p.z() > min_depth)) continue;
    whitened.push_back((camera_.project(p) - observed[i]).norm() / sigma[i]);
  }
  // Too few to measure a noise: ORB-SLAM2's width (refine_pose needs 3 matches to move at all).
  if (whitened.size() < kMinMatchesForNoise) return config_.huber_delta;
  const double scale = hbos::detail::rayleigh_scale(whitened, whitened.size(), 0.5);
  return config_.huber_delta * std::clamp(scale, config_.min_noise_scale, 1.0);
}

Eigen::Index PoseRefiner::refine(const std::vector<Eigen::Vector3d>& points_prev,
                                 const std::vector<Eigen::Vector2d>& observed,
                                 const std::vector<double>& sigma,
                                 const std::vector<std::uint8_t>& use,
                                 Eigen::Isometry3d& T_cur_prev) const {
  hbos::PoseRefinementOptions options;
  options.max_iterations = config_.max_iterations;
  options.huber_delta = huber_width(points_prev, observed, sigma, use, T_cur_prev);
  const auto at = [](Eigen::Index i) { return static_cast<std::size_t>(i); };
  const hbos::PoseRefinementSummary summary = hbos::refine_pose(
      static_cast<Eigen::Index>(points_prev.size()),
      [&](Eigen::Index i) { return points_prev[at(i)]; },
      [&](Eigen::Index i) { return observed[at(i)]; }, [&](Eigen::Index i) { return sigma[at(i)]; },
      [&](Eigen::Index i) { return use[at(i)] != 0; }, camera_, T_cur_prev, options);
  return summary.used;
}

}  // namespace hbos::slam
