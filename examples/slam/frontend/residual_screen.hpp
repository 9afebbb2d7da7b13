#pragma once
/// \file
/// Stage 4: the residual screen. Each match's 3D point is reprojected with the rough pose; the
/// residual to its keypoint is judged by hbos's reprojection screen (or a baseline), in
/// ORB-SLAM2-style rounds: screen -> refine the pose on the survivors -> re-screen.
///
/// This file (and residual_screen.cpp) is the front end's only contact with hbos's screening
/// headers (hbos/screening/), so a change there touches one place.

#include "frontend/config.hpp"
#include "frontend/pose_refiner.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace hbos::slam {

/// The names `--screen` accepts: default, paper, chi2, fixed, quantile, mad, none.
[[nodiscard]] const std::vector<std::string>& screen_strategy_names();

/// What the screen decided for one frame's matches (index i = match i).
struct ScreenOutcome {
  std::vector<std::uint8_t> inlier;  ///< 1 = kept
  std::vector<double> magnitude;     ///< the residual feature decided on (see `statistic`)
  std::vector<double> score;         ///< the strategy's score, higher = worse
  double threshold = std::numeric_limits<double>::quiet_NaN();  ///< cut on the score; NaN: none
  /// The cut in magnitude units where the strategy is a gate on the magnitude (fixed, chi2,
  /// quantile, mad); NaN for HBOS, whose cut is on a histogram score.
  double magnitude_cut = std::numeric_limits<double>::quiet_NaN();
  std::string statistic;   ///< "residual_px", "residual_whitened", "magnitude", ...
  std::string unit;        ///< "px" or "px/sigma"
  int rounds = 0;          ///< screenings run
  double screen_us = 0.0;  ///< [us] time spent screening (refinement rounds excluded)
  double refine_us = 0.0;  ///< [us] time of the refinements between rounds
};

class ResidualScreen {
 public:
  /// Throws hbos::InvalidArgument for an unknown strategy or invalid settings.
  explicit ResidualScreen(const ScreenStageConfig& config);
  ~ResidualScreen();
  ResidualScreen(ResidualScreen&&) noexcept;
  ResidualScreen& operator=(ResidualScreen&&) noexcept;

  /// Screens the matches (point `points_prev[i]` observed at `observed[i]`, scale sigma
  /// `sigma[i]`) under `T_cur_prev`, which the rounds refine in place with `refiner`. Points
  /// behind the camera under the pose are rejected without being screened.
  ScreenOutcome screen(const std::vector<Eigen::Vector3d>& points_prev,
                       const std::vector<Eigen::Vector2d>& observed,
                       const std::vector<double>& sigma, Eigen::Isometry3d& T_cur_prev,
                       const PoseRefiner& refiner);

  [[nodiscard]] const std::string& name() const { return config_.strategy; }

 private:
  struct Impl;
  ScreenStageConfig config_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hbos::slam
