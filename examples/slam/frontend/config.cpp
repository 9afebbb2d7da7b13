#include "frontend/config.hpp"

#include <hbos/error.hpp>

namespace hbos::slam {

double later_rounds_gate_floor(const Config& config) {
  if (config.screen.later_rounds_gate_floor) return *config.screen.later_rounds_gate_floor;
  if (config.tracker == TrackerKind::kMap) return 0.0;
  // The least gate 3 noise scales can be (the scale never falls below min_scale): no floor
  // beyond the noise scale's own.
  const hbos::NoiseGate gate;
  return gate.scales * gate.min_scale;
}

bool later_rounds_rigid_field(const Config& config) {
  return config.screen.later_rounds_rigid_field.value_or(true);
}

ScreenStageConfig screen_stage_for(const Config& config) {
  ScreenStageConfig stage = config.screen;
  stage.later_rounds_gate_floor = later_rounds_gate_floor(config);
  stage.later_rounds_rigid_field = later_rounds_rigid_field(config);
  return stage;
}

const char* to_string(MaskSource source) {
  switch (source) {
    case MaskSource::kNone:
      return "none";
    case MaskSource::kExact:
      return "exact";
    case MaskSource::kDegraded:
      return "degraded";
    case MaskSource::kDetector:
      return "detector";
    case MaskSource::kFiles:
      return "files";
  }
  return "?";
}

MaskSource parse_mask_source(const std::string& name) {
  for (const MaskSource s : {MaskSource::kNone, MaskSource::kExact, MaskSource::kDegraded,
                             MaskSource::kDetector, MaskSource::kFiles}) {
    if (name == to_string(s)) return s;
  }
  throw InvalidArgument("mask '" + name + "' is not one of none, exact, degraded, detector, files");
}

void ScreenStageConfig::select(const std::string& strategy_name) {
  if (strategy_name == "none") {
    screen.reset();
  } else {
    hbos::ScreenConfig parsed;
    parsed.strategy = hbos::parse_screen_strategy(strategy_name);  // throws naming the choices
    screen = parsed;
  }
  name = strategy_name;
}

nlohmann::json to_json(const LeverageGuardConfig& guard) {
  if (!guard.enabled) return false;
  return {{"radius_px", guard.radius_px},
          {"max_ratio", guard.max_ratio},
          {"consistency_z", guard.consistency_z},
          {"bias_cell_px", guard.bias_cell_px}};
}

nlohmann::json to_json(const JumpLimit& limit) {
  return {{"max_m", limit.max_m},
          {"max_deg", limit.max_deg},
          {"max_from_prediction_m", limit.max_from_prediction_m},
          {"max_from_prediction_deg", limit.max_from_prediction_deg}};
}

nlohmann::json to_json(const PointNoiseConfig& noise) {
  if (!noise.enabled) return false;
  return {
      {"memory", noise.memory}, {"tolerance", noise.tolerance}, {"min_frames", noise.min_frames}};
}

nlohmann::json to_json(const NoiseHistoryConfig& history) {
  if (!history.enabled) return false;
  return {{"memory", history.memory}, {"ratio", history.ratio}, {"min_frames", history.min_frames}};
}

const char* to_string(RoughPoseMethod method) {
  return method == RoughPoseMethod::kRansac ? "ransac" : "constant-velocity";
}

RoughPoseMethod parse_rough_pose_method(const std::string& name) {
  if (name == "ransac") return RoughPoseMethod::kRansac;
  if (name == "constant-velocity") return RoughPoseMethod::kConstantVelocity;
  throw InvalidArgument("rough pose '" + name + "' is not one of ransac, constant-velocity");
}

}  // namespace hbos::slam
