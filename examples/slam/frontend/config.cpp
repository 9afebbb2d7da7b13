#include "frontend/config.hpp"

#include <hbos/error.hpp>

namespace hbos::slam {

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
  }
  return "?";
}

MaskSource parse_mask_source(const std::string& name) {
  for (const MaskSource s :
       {MaskSource::kNone, MaskSource::kExact, MaskSource::kDegraded, MaskSource::kDetector}) {
    if (name == to_string(s)) return s;
  }
  throw InvalidArgument("mask '" + name + "' is not one of none, exact, degraded, detector");
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
