#include "eval/evaluate.hpp"

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
  result.tracked = params.frame_stamps.empty()
                       ? compute_tracked_share(evaluated, gt, params.frame_rate)
                       : compute_tracked_share(evaluated, gt, params.frame_stamps);

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
