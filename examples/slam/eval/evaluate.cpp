#include "eval/evaluate.hpp"

#include <algorithm>
#include <vector>

namespace hbos::slam {

Evaluation evaluate(const Trajectory& gt, const Trajectory& est, const EvaluationParams& params) {
  Evaluation result;
  result.params = params;
  result.gt_name = gt.name;
  result.est_name = est.name;

  AteParams ate_params;
  ate_params.association = params.association;
  ate_params.est_scale = params.est_scale;
  const std::vector<Match> matches = associate(gt, est, params.association);
  result.ate = compute_ate(gt, est, matches, ate_params);
  if (params.sim3) {
    ate_params.alignment = AlignmentKind::kSim3;
    result.ate_sim3 = compute_ate(gt, est, matches, ate_params);
  }

  const auto evaluated = static_cast<Eigen::Index>(matches.size());
  if (params.frame_stamps.empty()) {
    // The evaluated estimate stamps on the ground-truth clock, sorted (the greedy association
    // promises no order of its pairs).
    std::vector<double> stamps;
    stamps.reserve(matches.size());
    for (const Match& m : matches) {
      stamps.push_back(est.stamps[static_cast<std::size_t>(m.est)] + params.association.offset);
    }
    std::sort(stamps.begin(), stamps.end());
    result.tracked = compute_tracked_share(stamps, gt);
  } else {
    result.tracked = compute_tracked_share(evaluated, gt, params.frame_stamps);
  }

  if (params.rpe) {
    RpeParams rpe_params;
    rpe_params.delta = params.rpe_delta;
    rpe_params.unit = params.rpe_unit;
    rpe_params.offset = params.association.offset;
    rpe_params.est_scale =
        params.est_scale * (result.ate_sim3 ? result.ate_sim3->alignment.scale : 1.0);
    result.rpe = compute_rpe(gt, est, rpe_params);
  }
  return result;
}

}  // namespace hbos::slam
