#pragma once
/// \file
/// The front-end settings both commands take (hbos-slam and hbos-dynbench): the screen's
/// evidence, the guards, the trackers' memory, the opt-ins and the screening rounds. Header-only:
/// only the commands parse options, so the front end's library does not compile CLI11.

#include "common/cli_switch.hpp"
#include "frontend/config.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace hbos::slam {

/// `--<option>-memory`: the weight of the past per frame in the running mean of each point's
/// squared residual that `--<option>` keeps.
inline void add_memory_option(CLI::App& app, const std::string& option, double& memory) {
  app.add_option("--" + option + "-memory", memory,
                 "with --" + option + ": weight of the past per frame in a point's running mean")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.99));
}

/// Registers the shared front-end options on `app`, bound to `c` (its values are the defaults
/// the help shows).
inline void add_front_end_options(CLI::App& app, Config& c) {
  using hbos::examples::add_switch;
  add_switch(app, "mask-evidence", c.screen.mask_evidence,
             "pass each match's distance to the dynamic-object mask to the screen (the default "
             "screen's mask-neighbourhood evidence)");
  add_switch(app, "track-history", c.screen.track_history,
             "frame tracker: pass each match chain's forgetting-weighted outlier share to the "
             "screen (the default screen's persistence evidence)");
  add_switch(app, "provisional-consensus", c.screen.provisional_consensus,
             "map tracker: the default screen takes a new point's coherence over the other new "
             "points around it too, so a group of them moving together is caught");
  add_switch(app, "history-consensus", c.rough_pose.history_consensus,
             "frame tracker: when RANSAC's consensus leans on tracks the screen mostly rejected "
             "before, also try the consensus of the tracks it mostly kept and take the better "
             "remembered one (needs --track-history; any screen)");
  add_switch(app, "leverage-guard", c.guard.enabled,
             "drop the survivors near the dynamic-object mask when they alone would decide a "
             "direction of the pose (the mask neighbourhood's leverage guard; any screen)");
  app.add_option("--history-forgetting", c.map.history.forgetting,
                 "weight of the past per screening in the outlier shares both trackers keep")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  add_switch(app, "local-ba", c.map.local_bundle.enabled,
             "map tracker: bundle-adjust the new keyframe, its covisible neighbours and the "
             "points the screen vouches for whenever a keyframe is inserted "
             "(docs/map_tracking.md)");
  add_switch(app, "point-noise", c.map.point_noise.enabled,
             "map tracker: the final refinement weighs each map point by the noise its residuals "
             "have shown over the last frames, where that stands out from the frame's points "
             "(frontend/map/point_noise.hpp)");
  app.add_option("--point-noise-tolerance", c.map.point_noise.tolerance,
                 "with --point-noise: a point keeps its full weight up to this many times the "
                 "median mean squared residual of the frame's refined points")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 100.0));
  add_memory_option(app, "point-noise", c.map.point_noise.memory);
  add_switch(app, "noise-history", c.map.noise_history.enabled,
             "map tracker: a point whose residual under the refined poses has stayed well above "
             "the frame's typical one counts, for the default screen's history evidence, as a "
             "point it rejected before (frontend/map/noise_history.hpp)");
  app.add_option("--noise-history-ratio", c.map.noise_history.ratio,
                 "with --noise-history: a point's mean squared residual this many times the "
                 "frame's median counts as a rejection share of one half")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 100.0));
  add_memory_option(app, "noise-history", c.map.noise_history.memory);
  add_switch(app, "huber-from-noise", c.refinement.huber_from_noise,
             "scale the pose refinement's Huber width (2.447 px/sigma, ORB-SLAM2's) by the noise "
             "the refined matches have, never wider (docs/slam_demo.md)");
  app.add_option_function<double>(
         "--later-rounds-floor", [&c](double floor) { c.screen.later_rounds_gate_floor = floor; },
         "the default screen's noise-gate floor [px/sigma] in the rounds after the first "
         "refinement; 0 = the first round's (chi^2's 2.447) in every round (default: the "
         "tracker's own: frame 1.22 = 3 x the least noise scale, map 0; docs/results.md)")
      ->check(CLI::Range(0.0, 100.0));
  app.add_option_function<std::string>(
         "--later-rounds-field",
         [&c](const std::string& model) { c.screen.later_rounds_rigid_field = model == "rigid"; },
         "the field the default screen refits on the matches that look static in the rounds "
         "after the first refinement: rigid (the pixel shift of a small camera motion) or affine "
         "(default: rigid, for both trackers; docs/results.md)")
      ->check(CLI::IsMember({"rigid", "affine"}));
  app.add_option("--prediction-limit-m", c.jump_limit.max_from_prediction_m,
                 "both trackers: the farthest [m] a RANSAC rough pose may put the camera from the "
                 "constant-velocity prediction; beyond it the prediction is the rough pose")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--prediction-limit-deg", c.jump_limit.max_from_prediction_deg,
                 "the same for the orientation [deg]")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 180.0));
  app.add_option("--rounds", c.screen.rounds, "screen -> refine -> re-screen rounds")
      ->capture_default_str()
      ->check(CLI::Range(1, 20));
}

}  // namespace hbos::slam
