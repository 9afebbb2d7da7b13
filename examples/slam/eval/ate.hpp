#pragma once
/// \file
/// Absolute trajectory error (ATE) as TUM's evaluate_ate.py, plus a Sim(3) variant for
/// monocular (scale-free) estimates.

#include "eval/alignment.hpp"
#include "eval/associate.hpp"
#include "eval/statistics.hpp"
#include "eval/trajectory.hpp"

#include <Eigen/Core>

#include <vector>

namespace hbos::slam {

/// How the estimate is aligned to the ground truth before positions are compared.
enum class AlignmentKind {
  kSe3,   ///< rotation + translation (Horn), as evaluate_ate.py; for stereo / RGB-D
  kSim3,  ///< rotation + translation + scale (Umeyama); for monocular estimates
};

/// Parameters of compute_ate(); defaults are evaluate_ate.py's.
struct AteParams {
  AssociationParams association{};                ///< stamp matching (associate.py)
  AlignmentKind alignment = AlignmentKind::kSe3;  ///< kSim3 for monocular estimates
  /// Fixed factor on the estimate's positions before alignment (evaluate_ate.py --scale).
  double est_scale = 1.0;  ///< [-]
};

/// The ATE of one estimate against the ground truth.
struct AteResult {
  AlignmentKind alignment_kind = AlignmentKind::kSe3;
  std::vector<Match> matches;          ///< associated pairs, sorted by ground-truth stamp
  Similarity3 alignment;               ///< maps scaled estimate positions onto the ground truth
  Eigen::Matrix3Xd gt_positions;       ///< [m] per match
  Eigen::Matrix3Xd aligned_positions;  ///< [m] per match: alignment.apply(est_scale · p_est)
  Eigen::VectorXd errors;              ///< [m] per match: ‖aligned − gt‖
  ErrorStatistics stats;               ///< [m] of `errors`; stats.rmse is "the ATE"
  Eigen::Index n_gt_poses = 0;         ///< poses in the ground truth
  Eigen::Index n_est_poses = 0;        ///< poses in the estimate
};

/// Associates, aligns and measures, as evaluate_ate.py (kSe3) or with Umeyama's scale (kSim3).
/// Only positions enter the ATE; orientations are not compared. Throws hbos::InvalidArgument on
/// invalid trajectories or parameters and when fewer than 2 pairs associate (the script
/// refuses that too: "Couldn't find matching timestamp pairs").
[[nodiscard]] AteResult compute_ate(const Trajectory& gt, const Trajectory& est,
                                    const AteParams& params = {});

/// As compute_ate, on given associations (e.g. one association shared by the SE(3) and the
/// Sim(3) ATE). `params.association` is ignored.
[[nodiscard]] AteResult compute_ate(const Trajectory& gt, const Trajectory& est,
                                    const std::vector<Match>& matches,
                                    const AteParams& params = {});

}  // namespace hbos::slam
