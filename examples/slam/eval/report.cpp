#include "eval/report.hpp"

#include <fmt/format.h>

#include <iterator>
#include <vector>

namespace hbos::slam {

namespace {

nlohmann::json statistics_json(const ErrorStatistics& s) {
  return {{"rmse", s.rmse},   {"mean", s.mean}, {"median", s.median},
          {"std", s.std_dev}, {"min", s.min},   {"max", s.max}};
}

nlohmann::json ate_json(const AteResult& ate) {
  nlohmann::json j = statistics_json(ate.stats);
  j["alignment"] = ate.alignment_kind == AlignmentKind::kSe3 ? "se3" : "sim3";
  j["compared_pose_pairs"] = ate.stats.count;
  j["n_gt_poses"] = ate.n_gt_poses;
  j["n_est_poses"] = ate.n_est_poses;
  nlohmann::json rotation = nlohmann::json::array();
  for (Eigen::Index r = 0; r < 3; ++r) {
    rotation.push_back(
        {ate.alignment.rotation(r, 0), ate.alignment.rotation(r, 1), ate.alignment.rotation(r, 2)});
  }
  j["rotation_est_to_gt"] = rotation;
  j["translation_est_to_gt"] = {ate.alignment.translation.x(), ate.alignment.translation.y(),
                                ate.alignment.translation.z()};
  j["scale"] = ate.alignment.scale;
  return j;
}

std::string describe_delta(double delta, RpeDeltaUnit unit) {
  switch (unit) {
    case RpeDeltaUnit::kSeconds:
      return fmt::format("{} s", delta);
    case RpeDeltaUnit::kFrames:
      return fmt::format("{} frames", delta);
    case RpeDeltaUnit::kMetresAlongGt:
      return fmt::format("{} m travelled along the ground truth", delta);
  }
  return "?";
}

}  // namespace

const char* to_string(RpeDeltaUnit unit) {
  switch (unit) {
    case RpeDeltaUnit::kSeconds:
      return "s";
    case RpeDeltaUnit::kFrames:
      return "frames";
    case RpeDeltaUnit::kMetresAlongGt:
      return "m";
  }
  return "?";
}

nlohmann::json to_json(const Evaluation& evaluation) {
  const EvaluationParams& p = evaluation.params;
  nlohmann::json j;
  j["groundtruth"] = evaluation.gt_name;
  j["estimate"] = evaluation.est_name;
  j["settings"] = {{"max_difference_s", p.association.max_difference},
                   {"offset_s", p.association.offset},
                   {"est_scale", p.est_scale},
                   {"sim3", p.sim3},
                   {"rpe", p.rpe},
                   {"rpe_delta", p.rpe_delta},
                   {"rpe_delta_unit", to_string(p.rpe_unit)},
                   {"rpe_fixed_delta", true}};
  j["ate"] = ate_json(evaluation.ate);
  if (evaluation.ate_sim3) j["ate_sim3"] = ate_json(*evaluation.ate_sim3);
  const TrackedShare& t = evaluation.tracked;
  j["tracked"] = {{"evaluated_poses", t.evaluated_poses},
                  {"sequence_frames", t.sequence_frames},
                  {"share", t.share},
                  {"span_begin_s", t.span_begin},
                  {"span_end_s", t.span_end},
                  {"basis", t.basis}};
  if (t.basis == "estimate spacing") j["tracked"]["frame_period_s"] = t.frame_period;
  if (evaluation.rpe) {
    const RpeResult& r = *evaluation.rpe;
    j["rpe"] = {
        {"compared_pose_pairs", r.trans_m.count},
        {"n_gt_poses", r.n_gt_poses},
        {"n_est_poses", r.n_est_poses},
        {"n_candidate_pairs", r.n_candidates},
        {"n_pairs_with_i_equal_j", r.n_pairs_with_i_equal_j},
        {"n_candidate_pairs_with_i_equal_j", r.n_candidates_with_i_equal_j},
        {"est_scale", evaluation.params.est_scale *
                          (evaluation.ate_sim3 ? evaluation.ate_sim3->alignment.scale : 1.0)},
        {"gt_max_time_difference_s", r.gt_max_time_difference},
        {"trans_m", statistics_json(r.trans_m)},
        {"rot_deg", statistics_json(r.rot_deg)}};
  }
  return j;
}

std::string format_report(const Evaluation& evaluation) {
  const EvaluationParams& p = evaluation.params;
  const AteResult& ate = evaluation.ate;
  std::string out;
  auto line = [&out](const std::string& text) { out += text + "\n"; };

  line("Trajectory evaluation (TUM RGB-D benchmark conventions)");
  line(fmt::format("  ground truth  {}  ({} poses)", evaluation.gt_name, ate.n_gt_poses));
  line(fmt::format("  estimate      {}  ({} poses)", evaluation.est_name, ate.n_est_poses));
  line(
      fmt::format("  association   |dt| < {} s (strict), offset {} s, greedy one-to-one "
                  "(associate.py): {} pairs",
                  p.association.max_difference, p.association.offset, ate.stats.count));
  if (p.est_scale != 1.0) line(fmt::format("  est. scale    {} (fixed, --scale)", p.est_scale));
  line("");

  struct Column {
    std::string title;
    std::string unit;
    const ErrorStatistics* stats;
  };
  std::vector<Column> columns = {{"ATE SE(3)", "[m]", &ate.stats}};
  if (evaluation.ate_sim3) columns.push_back({"ATE Sim(3)", "[m]", &evaluation.ate_sim3->stats});
  if (evaluation.rpe) {
    columns.push_back({"RPE transl.", "[m]", &evaluation.rpe->trans_m});
    columns.push_back({"RPE rot.", "[deg]", &evaluation.rpe->rot_deg});
  }
  auto row = [&](const std::string& label, auto cell) {
    std::string text = fmt::format("  {:<18}", label);
    for (const Column& c : columns) text += fmt::format("{:>14}", cell(c));
    line(text);
  };
  row("", [](const Column& c) { return c.title; });
  row("", [](const Column& c) { return c.unit; });
  row("pairs", [](const Column& c) { return fmt::format("{}", c.stats->count); });
  row("RMSE", [](const Column& c) { return fmt::format("{:.6f}", c.stats->rmse); });
  row("mean", [](const Column& c) { return fmt::format("{:.6f}", c.stats->mean); });
  row("median", [](const Column& c) { return fmt::format("{:.6f}", c.stats->median); });
  row("std (population)", [](const Column& c) { return fmt::format("{:.6f}", c.stats->std_dev); });
  row("min", [](const Column& c) { return fmt::format("{:.6f}", c.stats->min); });
  row("max", [](const Column& c) { return fmt::format("{:.6f}", c.stats->max); });
  line("");

  if (evaluation.ate_sim3) {
    line(fmt::format("  Sim(3) scale (est -> gt): {:.6f}", evaluation.ate_sim3->alignment.scale));
  }
  const TrackedShare& t = evaluation.tracked;
  const std::string frames_from =
      t.basis == "estimate spacing"
          ? fmt::format(
                "counted from the estimate's {:.1f} ms spacing; --frames rgb.txt counts "
                "exactly",
                1e3 * t.frame_period)
          : "frame list";
  line(
      fmt::format("  tracked: {} evaluated poses / {} frames ({}) over the {:.1f} s "
                  "ground-truth span = {:.1f} %",
                  t.evaluated_poses, t.sequence_frames, frames_from, t.span_end - t.span_begin,
                  100.0 * t.share));
  if (evaluation.rpe) {
    const RpeResult& r = *evaluation.rpe;
    line(
        fmt::format("  RPE: fixed delta {} (evaluate_rpe.py --fixed_delta); both ends need ground "
                    "truth within {:.4f} s (2 x median GT period, not the ATE's {} s)",
                    describe_delta(p.rpe_delta, p.rpe_unit), r.gt_max_time_difference,
                    p.association.max_difference));
    if (evaluation.ate_sim3) {
      line("  RPE: estimate translations scaled by the Sim(3) scale before comparing");
    }
    if (r.n_pairs_with_i_equal_j > 0) {
      line(
          fmt::format("  warning: {} RPE pairs compare a pose with itself (estimate gap longer "
                      "than twice the delta); their error is 0",
                      r.n_pairs_with_i_equal_j));
    }
  }
  line("  note: \"ATE\" in TUM / ORB-SLAM / DynaSLAM tables is the RMSE row; evaluate_rpe.py");
  line("        without --verbose prints only the *mean* translational RPE. Quote which one.");
  return out;
}

}  // namespace hbos::slam
