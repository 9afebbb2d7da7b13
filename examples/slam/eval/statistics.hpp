#pragma once
/// \file
/// The summary statistics the TUM scripts print for a vector of errors.

#include <Eigen/Core>

namespace hbos::slam {

/// Summary of n >= 1 errors, with numpy's conventions as used by evaluate_ate.py and
/// evaluate_rpe.py. Papers mix these up: "ATE" in TUM, ORB-SLAM and DynaSLAM tables is the RMSE,
/// while evaluate_rpe.py without --verbose prints only the *mean* translational error.
struct ErrorStatistics {
  Eigen::Index count = 0;
  double rmse = 0.0;     ///< sqrt(Σ e² / n)
  double mean = 0.0;     ///< Σ e / n
  double median = 0.0;   ///< middle value; mean of the two middle values for even n (numpy)
  double std_dev = 0.0;  ///< population standard deviation, sqrt(Σ (e − mean)² / n) (ddof = 0)
  double min = 0.0;
  double max = 0.0;

  /// Statistics of angles in radians converted to degrees as evaluate_rpe.py does it: *after*
  /// taking the statistic, each value as `value * 180.0 / pi` (in that order, for bit parity).
  [[nodiscard]] ErrorStatistics radians_to_degrees() const;
};

/// Statistics of `errors`; throws hbos::InvalidArgument when empty or not finite.
[[nodiscard]] ErrorStatistics compute_statistics(const Eigen::VectorXd& errors);

}  // namespace hbos::slam
