#include "frontend/map/keyframe_policy.hpp"

namespace hbos::slam {

bool need_keyframe(const KeyframeEvidence& e, const KeyframeConfig& c) {
  if (e.frames_since_relocalisation < c.max_frames && e.keyframes_in_map > c.max_frames) {
    return false;
  }
  const bool close =
      e.tracked_close < c.tracked_close_min && e.untracked_close > c.untracked_close_min;
  const float ratio = e.keyframes_in_map < 2 ? 0.4f : c.reference_ratio;
  const auto tracked = static_cast<float>(e.tracked);
  const auto reference = static_cast<float>(e.reference_tracked);
  const bool c1a = e.frames_since_keyframe >= c.max_frames;
  const bool c1b = e.frames_since_keyframe >= c.min_frames;  // local mapping is always idle
  const bool c1c = tracked < 0.25f * reference || close;
  const bool c2 = (tracked < ratio * reference || close) && e.tracked > c.min_tracked;
  return (c1a || c1b || c1c) && c2;
}

}  // namespace hbos::slam
