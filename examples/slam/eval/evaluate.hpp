#pragma once
/// \file
/// One call for the whole evaluation of an estimate: association, SE(3) ATE, optional Sim(3)
/// ATE, share tracked and RPE. What `hbos-eval` and the front end's benchmarks report.

#include "eval/associate.hpp"
#include "eval/ate.hpp"
#include "eval/rpe.hpp"
#include "eval/tracked_share.hpp"
#include "eval/trajectory.hpp"

#include <optional>
#include <string>
#include <vector>

namespace hbos::slam {

/// Parameters of evaluate(); every default reproduces the TUM scripts' defaults (RPE with
/// --fixed_delta).
struct EvaluationParams {
  AssociationParams association{};  ///< ATE stamp matching; its offset also applies to the RPE
  /// Fixed factor on the estimate's positions (the scripts' --scale).
  double est_scale = 1.0;  ///< [-]
  /// Also compute the Sim(3) ATE (for monocular estimates). Its scale then also multiplies the
  /// estimate's relative translations in the RPE, as evo does with --correct_scale.
  bool sim3 = false;
  bool rpe = true;                                 ///< compute the RPE
  double rpe_delta = 1.0;                          ///< [s], [frames] or [m], see rpe_unit
  RpeDeltaUnit rpe_unit = RpeDeltaUnit::kSeconds;  ///< unit of rpe_delta
  /// Camera frame stamps of the sequence (rgb.txt) for the share tracked; when empty, the
  /// frames are counted from the spacing of the evaluated estimate stamps (see
  /// compute_tracked_share).
  std::vector<double> frame_stamps;
};

/// Everything evaluate() measured.
struct Evaluation {
  std::string gt_name;                ///< Trajectory::name of the ground truth
  std::string est_name;               ///< Trajectory::name of the estimate
  AteResult ate;                      ///< SE(3) ATE, always
  std::optional<AteResult> ate_sim3;  ///< when EvaluationParams::sim3
  TrackedShare tracked;               ///< share of the sequence in the ATE
  std::optional<RpeResult> rpe;       ///< when EvaluationParams::rpe
  EvaluationParams params;            ///< as used

  /// The ATE a reader should quote: Sim(3) when it was asked for (monocular), else SE(3).
  [[nodiscard]] const AteResult& main_ate() const { return ate_sim3 ? *ate_sim3 : ate; }
};

/// Runs the whole evaluation. The SE(3) and Sim(3) ATE share one association. Throws
/// hbos::InvalidArgument on invalid input or when a metric cannot be computed (see compute_ate,
/// compute_rpe, compute_tracked_share).
[[nodiscard]] Evaluation evaluate(const Trajectory& gt, const Trajectory& est,
                                  const EvaluationParams& params = {});

}  // namespace hbos::slam
