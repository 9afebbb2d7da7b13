#pragma once
/// \file
/// Relative pose error (RPE) as TUM's `evaluate_rpe.py --fixed_delta`.
///
/// Always a fixed delta: without --fixed_delta the script compares *random* pose pairs (10000
/// draws of `random.randint` after `random.seed(0)`, including i = j and j < i, with arbitrary
/// time gaps), and Python 2 and 3 draw different pairs from the same seed, so such numbers are
/// neither meaningful per delta nor reproducible. There is deliberately no such mode here.

#include "eval/statistics.hpp"
#include "eval/trajectory.hpp"

#include <Eigen/Core>

#include <vector>

namespace hbos::slam {

/// The unit of the RPE delta.
enum class RpeDeltaUnit {
  kSeconds,  ///< delta in estimate time (evaluate_rpe.py --delta_unit s)
  kFrames,   ///< delta in estimate poses (--delta_unit f); delta must be a whole number
  /// delta in metres travelled along the **ground truth** (pose i's distance is that of its
  /// nearest ground-truth pose). evaluate_rpe.py's `m` uses the *estimate's* own path length,
  /// so there a wrongly scaled or jittery estimate changes which pairs are compared; along the
  /// ground truth the pairs depend on the sequence only.
  kMetresAlongGt,
};

/// Parameters of compute_rpe(); defaults are evaluate_rpe.py's with --fixed_delta.
struct RpeParams {
  double delta = 1.0;                          ///< [s], [frames] or [m], see unit
  RpeDeltaUnit unit = RpeDeltaUnit::kSeconds;  ///< unit of delta
  double offset = 0.0;                         ///< [s] added to estimate stamps (--offset)
  /// Fixed factor on the estimate's relative translations (--scale); for a monocular estimate,
  /// the Sim(3) scale.
  double est_scale = 1.0;  ///< [-]
};

/// One compared pair of estimate poses (est0 → est1) and their nearest ground-truth poses.
struct RpePair {
  Eigen::Index est0 = 0;     ///< estimate index i
  Eigen::Index est1 = 0;     ///< estimate index j, the pose closest to "i + delta"
  Eigen::Index gt0 = 0;      ///< ground-truth pose nearest to est0
  Eigen::Index gt1 = 0;      ///< ground-truth pose nearest to est1
  double trans_error = 0.0;  ///< [m] ‖translation of E‖ with E = (E_j⁻¹E_i)⁻¹ (G_j⁻¹G_i)
  double rot_error = 0.0;    ///< [rad] arccos(clamp((tr R_E − 1) / 2))
};

/// The RPE of one estimate against the ground truth.
struct RpeResult {
  std::vector<RpePair> pairs;
  ErrorStatistics trans_m;  ///< [m] statistics of the translational errors
  ErrorStatistics rot_deg;  ///< [deg] statistics of the rotational errors (taken in rad, then
                            ///< converted, as the script does)
  /// [s] the ground-truth stamp tolerance: 2 × median ground-truth period, *not* the 0.02 s of
  /// the ATE association (≈ 0.02 s for 100 Hz TUM ground truth, ≈ 0.067 s for 30 Hz Bonn).
  double gt_max_time_difference = 0.0;
  /// Compared pairs with est0 == est1 (after an estimate gap longer than 2 × delta, the pose
  /// nearest to "t + delta" is the pose itself); their error is 0.
  Eigen::Index n_pairs_with_i_equal_j = 0;
  Eigen::Index n_candidates = 0;                 ///< (i, j) pairs before the ground-truth check
  Eigen::Index n_candidates_with_i_equal_j = 0;  ///< of those, pairs with est0 == est1
  Eigen::Index n_gt_poses = 0;
  Eigen::Index n_est_poses = 0;
};

/// The RPE as evaluate_rpe.py with --fixed_delta (its default delta 1 s):
///  1. for every estimate index i, j = the index whose "position" (stamp, frame number, or GT
///     distance) is closest to i's plus delta, by the script's binary search; the pair is
///     dropped when j is the *last* estimate pose (a quirk kept for parity);
///  2. each of i, j takes its nearest ground-truth pose by stamp; the pair is skipped when
///     either is more than gt_max_time_difference away;
///  3. E = (E_j⁻¹ E_i)⁻¹ (G_j⁻¹ G_i), with the estimate's relative translation times est_scale;
///     trans = ‖t_E‖, rot = arccos(min(1, max(−1, (tr R_E − 1) / 2))).
/// Unlike the script, there is no cap of 10000 pairs (above it, the script samples randomly).
/// Throws hbos::InvalidArgument on invalid input, when fewer than 2 estimate poses overlap the
/// ground truth in time, or when fewer than 2 pairs remain (the script raises in both cases).
[[nodiscard]] RpeResult compute_rpe(const Trajectory& gt, const Trajectory& est,
                                    const RpeParams& params = {});

/// The script's find_closest_index on a sorted list: a binary search that remembers the probed
/// element nearest to t (replacing it only when strictly nearer) and returns at once on an
/// exact hit. It finds the nearest element; on a tie, whichever was probed first. Exposed for
/// tests and for the front end's stamp lookups. `values` must be non-empty and sorted.
[[nodiscard]] Eigen::Index find_closest_index(const std::vector<double>& values, double t);

}  // namespace hbos::slam
