#include "eval/eval_command.hpp"

#include "common/atomic_file.hpp"
#include "common/cli_validators.hpp"
#include "eval/evaluate.hpp"
#include "eval/plot.hpp"
#include "eval/report.hpp"
#include "eval/trajectory_io.hpp"

#include <CLI/CLI.hpp>
#include <hbos/error.hpp>
#include <hbos/version.hpp>
#include <nlohmann/json.hpp>

#include <map>
#include <ostream>
#include <stdexcept>
#include <string>

namespace hbos::slam {

namespace {

struct CommandOptions {
  std::string gt_path;
  std::string est_path;
  double max_difference = 0.02;
  double offset = 0.0;
  double scale = 1.0;
  bool sim3 = false;
  bool no_rpe = false;
  double rpe_delta = 1.0;
  std::string rpe_unit = "s";
  std::string frames_path;
  std::string json_path;
  std::string plot_dir;
  std::string plot_plane = "xy";
  bool lenient_duplicates = false;
  double quaternion_tolerance = 1e-2;
};

void add_options(CLI::App& app, CommandOptions& o) {
  app.add_option("groundtruth", o.gt_path, "ground-truth trajectory, TUM format")->required();
  app.add_option("estimate", o.est_path, "estimated trajectory, TUM format")->required();
  app.add_option("--max-diff", o.max_difference,
                 "ATE association: pairs need |dt| strictly below this [s] (associate.py)")
      ->capture_default_str()
      ->check(examples::non_negative_number());
  app.add_option("--offset", o.offset, "added to every estimate stamp [s]")->capture_default_str();
  app.add_option("--scale", o.scale, "fixed factor on estimate positions (the scripts' --scale)")
      ->capture_default_str()
      ->check(examples::positive_number());
  app.add_flag("--sim3", o.sim3,
               "also align with scale (Umeyama Sim(3)), for monocular estimates; the plots and "
               "the RPE then use that scale");
  app.add_flag("--no-rpe", o.no_rpe, "skip the relative pose error");
  app.add_option("--rpe-delta", o.rpe_delta, "RPE delta, in --rpe-unit (always a fixed delta)")
      ->capture_default_str()
      ->check(examples::positive_number());
  app.add_option("--rpe-unit", o.rpe_unit,
                 "s: estimate time; frames: estimate poses; m: metres travelled along the ground "
                 "truth")
      ->capture_default_str()
      ->check(CLI::IsMember({"s", "frames", "m"}));
  app.add_option("--frames", o.frames_path,
                 "the sequence's rgb.txt (first column: frame stamps), to count frames for the "
                 "share tracked (without it, frames are counted from the spacing of the "
                 "estimate's stamps)");
  app.add_option("--json", o.json_path, "write the results as JSON to this file (atomically)")
      ->check(examples::non_empty_path());
  app.add_option("--plot", o.plot_dir, "write PNG plots into this directory")
      ->check(examples::non_empty_path());
  app.add_option("--plot-plane", o.plot_plane, "projection of the top view")
      ->capture_default_str()
      ->check(CLI::IsMember({"xy", "xz", "yz"}));
  app.add_flag("--lenient-duplicates", o.lenient_duplicates,
               "accept repeated and unsorted stamps like the TUM scripts (sort, keep the last "
               "line of a repeated stamp) instead of failing");
  app.add_option("--quaternion-tolerance", o.quaternion_tolerance,
                 "reject quaternions whose norm differs from 1 by more than this")
      ->capture_default_str()
      ->check(examples::non_negative_number());
}

Trajectory read_input(const std::string& path, const ReadOptions& options, const char* role,
                      nlohmann::json& inputs, std::ostream& err) {
  ReadReport report;
  Trajectory trajectory = read_tum_trajectory(path, options, &report);
  for (const std::string& warning : report.warnings) {
    err << "hbos-eval: warning: " << warning << "\n";
  }
  inputs[role] = {{"path", path},
                  {"poses", report.poses},
                  {"data_lines", report.data_lines},
                  {"duplicates_dropped", report.duplicates_dropped},
                  {"reordered", report.reordered}};
  return trajectory;
}

int run(const CommandOptions& o, std::ostream& out, std::ostream& err) {
  ReadOptions read_options;
  read_options.stamps = o.lenient_duplicates ? StampPolicy::kLikeTumScripts : StampPolicy::kStrict;
  read_options.max_quaternion_norm_error = o.quaternion_tolerance;

  for (const std::string& input : {o.gt_path, o.est_path, o.frames_path}) {
    detail::require(!examples::is_same_file(o.json_path, input), "--json '", o.json_path,
                    "' is the input file '", input, "' itself: the results would replace it");
  }
  nlohmann::json inputs;
  const Trajectory gt = read_input(o.gt_path, read_options, "groundtruth", inputs, err);
  const Trajectory est = read_input(o.est_path, read_options, "estimate", inputs, err);

  EvaluationParams params;
  params.association.max_difference = o.max_difference;
  params.association.offset = o.offset;
  params.est_scale = o.scale;
  params.sim3 = o.sim3;
  params.rpe = !o.no_rpe;
  params.rpe_delta = o.rpe_delta;
  const std::map<std::string, RpeDeltaUnit> units = {{"s", RpeDeltaUnit::kSeconds},
                                                     {"frames", RpeDeltaUnit::kFrames},
                                                     {"m", RpeDeltaUnit::kMetresAlongGt}};
  params.rpe_unit = units.at(o.rpe_unit);
  if (!o.frames_path.empty()) params.frame_stamps = read_frame_stamps(o.frames_path);

  const Evaluation evaluation = evaluate(gt, est, params);
  out << format_report(evaluation);

  try {
    if (!o.json_path.empty()) {
      nlohmann::json j = to_json(evaluation);
      j["tool"] = "hbos-eval";
      j["hbos_version"] = std::to_string(kVersionMajor) + "." + std::to_string(kVersionMinor) +
                          "." + std::to_string(kVersionPatch);
      j["inputs"] = inputs;
      j["settings"]["stamp_policy"] = o.lenient_duplicates ? "like_tum_scripts" : "strict";
      j["settings"]["quaternion_tolerance"] = o.quaternion_tolerance;
      examples::write_file_atomically(o.json_path, j.dump(1) + "\n");
      out << "wrote " << o.json_path << "\n";
    }
    if (!o.plot_dir.empty()) {
      PlotParams plot_params;
      plot_params.plane = o.plot_plane == "xy"   ? PlotPlane::kXY
                          : o.plot_plane == "xz" ? PlotPlane::kXZ
                                                 : PlotPlane::kYZ;
      for (const std::string& path : write_plots(o.plot_dir, gt, est, evaluation, plot_params)) {
        out << "wrote " << path << "\n";
      }
    }
  } catch (const std::runtime_error& e) {
    err << "hbos-eval: error: " << e.what() << "\n";
    return kEvalOutputError;
  }
  return kEvalOk;
}

}  // namespace

int run_eval_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  CLI::App app{
      "Evaluates an estimated camera trajectory against ground truth exactly as the TUM RGB-D "
      "benchmark scripts do (associate.py, evaluate_ate.py, evaluate_rpe.py --fixed_delta). "
      "Trajectories are TUM files: 't tx ty tz qx qy qz qw' per line. Exit status: 0 ok, "
      "1 output not written, 2 bad input.",
      "hbos-eval"};
  CommandOptions options;
  add_options(app, options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e, out, err) == 0 ? kEvalOk : kEvalBadInput;
  }
  try {
    return run(options, out, err);
  } catch (const InvalidArgument& e) {
    err << "hbos-eval: error: " << e.what() << "\n";
    return kEvalBadInput;
  }
}

}  // namespace hbos::slam
