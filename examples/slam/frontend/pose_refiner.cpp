#include "frontend/pose_refiner.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>
#include <hbos/screening/pose_refinement.hpp>

#include <cmath>

namespace hbos::slam {

PoseRefiner::PoseRefiner(const RefinementConfig& config, hbos::PinholeCamerad camera)
    : config_(config), camera_(camera) {
  if (config_.max_iterations < 1 || !(config_.huber_delta >= 0.0) ||
      !std::isfinite(config_.huber_delta)) {
    throw InvalidArgument(fmt::format(
        "refinement settings: iterations {} must be >= 1, Huber width {} finite and >= 0",
        config_.max_iterations, config_.huber_delta));
  }
}

Eigen::Index PoseRefiner::refine(const std::vector<Eigen::Vector3d>& points_prev,
                                 const std::vector<Eigen::Vector2d>& observed,
                                 const std::vector<double>& sigma,
                                 const std::vector<std::uint8_t>& use,
                                 Eigen::Isometry3d& T_cur_prev) const {
  hbos::PoseRefinementOptions options;
  options.max_iterations = config_.max_iterations;
  options.huber_delta = config_.huber_delta;
  const auto at = [](Eigen::Index i) { return static_cast<std::size_t>(i); };
  const hbos::PoseRefinementSummary summary = hbos::refine_pose(
      static_cast<Eigen::Index>(points_prev.size()),
      [&](Eigen::Index i) { return points_prev[at(i)]; },
      [&](Eigen::Index i) { return observed[at(i)]; }, [&](Eigen::Index i) { return sigma[at(i)]; },
      [&](Eigen::Index i) { return use[at(i)] != 0; }, camera_, T_cur_prev, options);
  return summary.used;
}

}  // namespace hbos::slam
