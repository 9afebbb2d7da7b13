#pragma once
/// \file
/// Stage 4: the residual screen. Each match's 3D point is reprojected with the rough pose; the
/// residual to its keypoint is judged by hbos's reprojection screen (or a baseline), in
/// ORB-SLAM2-style rounds: screen -> refine the pose on the survivors -> re-screen. The rounds
/// loop is written here: the library screens one round per call.
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

/// The names `--screen` accepts: those of hbos::named_strategies(), then `none`.
[[nodiscard]] const std::vector<std::string>& screen_strategy_names();

/// What the screen decided for one frame's matches (index i = match i).
struct ScreenOutcome {
  std::vector<std::uint8_t> inlier;  ///< 1 = kept
  std::vector<double> magnitude;     ///< the residual feature decided on (see `statistic`)
  std::vector<double> score;         ///< the strategy's score, higher = worse
  double threshold = std::numeric_limits<double>::quiet_NaN();  ///< cut on the score; NaN: none
  /// The cut in magnitude units where the decision is a gate on the magnitude (fixed, chi2,
  /// quantile, mad, and HBOS's noise gate); NaN otherwise (the literal and magnitude-only HBOS).
  double magnitude_cut = std::numeric_limits<double>::quiet_NaN();
  std::string statistic;   ///< "residual_px", "residual_whitened", "magnitude", ...
  std::string unit;        ///< of the magnitude: "px" or "px/sigma"
  std::string score_unit;  ///< of score and threshold: "score", "px", "px/sigma", "px^2/sigma^2"
  int rounds = 0;          ///< screenings run
  double screen_us = 0.0;  ///< [us] time spent screening (refinement rounds excluded)
  double refine_us = 0.0;  ///< [us] time of the refinements between rounds
};

/// Evidence about each match beyond its residual (index i = match i). Every field is optional:
/// an empty vector means "not available" and the screen does without it.
struct MatchEvidence {
  std::vector<double> mask_distance_px;  ///< [px] to the nearest masked pixel; inf: no mask
  /// The persistence prior the caller keeps per track or map point: in [0, 1], the
  /// forgetting-weighted share of past frames in which this point was screened out.
  std::vector<double> outlier_history;
  /// 1: the match is on probation: it is screened like any, but neither shapes the screen's fit
  /// (it is passed as flagged, under FlaggedPolicy::FitWithout) nor the pose refined between
  /// rounds. The map tracker sets it for map points the screen has not yet kept often enough.
  std::vector<std::uint8_t> provisional;
};

/// Takes the provisional matches (MatchEvidence::provisional) out of `use`, the matches a pose
/// is refined on, unless fewer than `min_survivors` others would remain (then `use` stays).
void keep_out_provisional(const std::vector<std::uint8_t>& provisional, int min_survivors,
                          std::vector<std::uint8_t>& use);

class ResidualScreen {
 public:
  /// Throws hbos::InvalidArgument for an unknown strategy or invalid settings.
  explicit ResidualScreen(const ScreenStageConfig& config);
  ~ResidualScreen();
  ResidualScreen(ResidualScreen&&) noexcept;
  ResidualScreen& operator=(ResidualScreen&&) noexcept;

  /// Screens the matches (point `points_prev[i]` observed at `observed[i]`, scale sigma
  /// `sigma[i]`) under `T_cur_prev`, which the rounds refine in place with `refiner`. Points
  /// behind the camera under the pose are rejected without being screened. `evidence` adds
  /// what the caller knows beyond the residuals (see MatchEvidence).
  ScreenOutcome screen(const std::vector<Eigen::Vector3d>& points_prev,
                       const std::vector<Eigen::Vector2d>& observed,
                       const std::vector<double>& sigma, Eigen::Isometry3d& T_cur_prev,
                       const PoseRefiner& refiner, const MatchEvidence& evidence = {});

  [[nodiscard]] const std::string& name() const { return config_.name; }

 private:
  struct Impl;
  ScreenStageConfig config_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hbos::slam
