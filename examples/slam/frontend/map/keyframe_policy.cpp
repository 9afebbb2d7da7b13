#include "frontend/map/keyframe_policy.hpp"

#include <algorithm>
#include <cstddef>

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

std::vector<int> select_new_points(const std::vector<float>& depth_m,
                                   const std::vector<std::uint8_t>& taken,
                                   const KeyframeConfig& c) {
  std::vector<int> fresh;
  for (std::size_t k = 0; k < depth_m.size(); ++k) {
    const bool is_taken = k < taken.size() && taken[k] != 0;
    if (!is_taken && depth_m[k] > 0.f) fresh.push_back(static_cast<int>(k));
  }
  const auto depth = [&](int k) { return depth_m[static_cast<std::size_t>(k)]; };
  std::sort(fresh.begin(), fresh.end(), [&](int a, int b) { return depth(a) < depth(b); });
  std::size_t close = 0;
  while (close < fresh.size() && depth(fresh[close]) < c.close_depth_m) ++close;
  const auto at_most = [&](int n) { return std::min(fresh.size(), static_cast<std::size_t>(n)); };
  const std::size_t far = std::min(fresh.size() - close, at_most(c.max_far_points));
  fresh.resize(std::max(close + far, at_most(c.min_new_points)));
  return fresh;
}

}  // namespace hbos::slam
