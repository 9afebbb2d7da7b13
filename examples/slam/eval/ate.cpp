#include "eval/ate.hpp"

#include <hbos/error.hpp>

#include <cmath>
#include <cstddef>

namespace hbos::slam {

AteResult compute_ate(const Trajectory& gt, const Trajectory& est,
                      const std::vector<Match>& matches, const AteParams& params) {
  check_trajectory(gt, "compute_ate: ground truth");
  check_trajectory(est, "compute_ate: estimate");
  detail::require(std::isfinite(params.est_scale) && params.est_scale > 0.0,
                  "compute_ate: est_scale must be finite and > 0, got ", params.est_scale);
  detail::require(
      matches.size() >= 2, "compute_ate: only ", matches.size(), " associated pose pairs between '",
      gt.name, "' and '", est.name,
      "'; need at least 2 (wrong files, or stamps offset by more than max_difference?)");

  const auto n = static_cast<Eigen::Index>(matches.size());
  AteResult result;
  result.alignment_kind = params.alignment;
  result.matches = matches;
  result.n_gt_poses = gt.size();
  result.n_est_poses = est.size();
  result.gt_positions.resize(3, n);
  Eigen::Matrix3Xd est_positions(3, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Match& m = matches[static_cast<std::size_t>(k)];
    detail::require(m.gt >= 0 && m.gt < gt.size() && m.est >= 0 && m.est < est.size(),
                    "compute_ate: match ", k, " (gt ", m.gt, ", est ", m.est, ") is out of range");
    result.gt_positions.col(k) = gt.positions.col(m.gt);
    est_positions.col(k) = est.positions.col(m.est) * params.est_scale;
  }
  result.alignment = params.alignment == AlignmentKind::kSe3
                         ? align_rigid(est_positions, result.gt_positions)
                         : align_similarity(est_positions, result.gt_positions);
  result.aligned_positions = result.alignment.apply(est_positions);
  result.errors = (result.aligned_positions - result.gt_positions).colwise().norm().transpose();
  for (Eigen::Index k = 0; k < result.errors.size(); ++k) {
    const Match& m = matches[static_cast<std::size_t>(k)];
    detail::require(std::isfinite(result.errors[k]), "compute_ate: the error of ", est.name,
                    " at stamp ", est.stamps[static_cast<std::size_t>(m.est)], " against ", gt.name,
                    " at stamp ", gt.stamps[static_cast<std::size_t>(m.gt)], " is not finite (",
                    result.errors[k], "): positions too large to align in double precision");
  }
  result.stats = compute_statistics(result.errors);
  return result;
}

AteResult compute_ate(const Trajectory& gt, const Trajectory& est, const AteParams& params) {
  check_trajectory(gt, "compute_ate: ground truth");
  check_trajectory(est, "compute_ate: estimate");
  return compute_ate(gt, est, associate(gt, est, params.association), params);
}

}  // namespace hbos::slam
