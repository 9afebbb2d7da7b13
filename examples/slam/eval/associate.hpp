#pragma once
/// \file
/// Timestamp association exactly as the TUM benchmark's `associate.py`.

#include "eval/trajectory.hpp"

#include <Eigen/Core>

#include <vector>

namespace hbos::slam {

/// Parameters of associate(); defaults are associate.py's.
struct AssociationParams {
  /// Pairs need |t_gt − (t_est + offset)| strictly below this. 0.02 s is associate.py's and
  /// evaluate_ate.py's default (evo's is 0.01 s, and evo accepts equality).
  double max_difference = 0.02;  ///< [s]
  double offset = 0.0;           ///< [s] added to every estimate stamp before comparing
};

/// One associated pair: indices into the ground-truth and the estimate trajectory.
struct Match {
  Eigen::Index gt = 0;   ///< index into the ground-truth stamps
  Eigen::Index est = 0;  ///< index into the estimate stamps
};

/// Associates two sorted stamp lists as associate.py does:
///  1. candidates are all pairs (a, b) with |a − (b + offset)| < max_difference (strict);
///  2. they are accepted greedily in order of increasing |a − (b + offset)|, ties broken by a,
///     then b, whenever neither a nor b is already taken, so the result is one-to-one;
///  3. the result is sorted by ground-truth stamp.
/// Runs in O((n + m) log(n + m) + k log k) for k candidates instead of the script's O(n·m), with
/// the same floating-point predicate, so the pairs are identical.
/// Throws hbos::InvalidArgument unless both lists strictly increase and are finite, and
/// max_difference and offset are finite with max_difference >= 0.
[[nodiscard]] std::vector<Match> associate(const std::vector<double>& gt_stamps,
                                           const std::vector<double>& est_stamps,
                                           const AssociationParams& params = {});

/// associate() on the stamps of two trajectories.
[[nodiscard]] std::vector<Match> associate(const Trajectory& gt, const Trajectory& est,
                                           const AssociationParams& params = {});

}  // namespace hbos::slam
