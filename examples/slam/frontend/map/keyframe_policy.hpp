#pragma once
/// \file
/// When a tracked frame becomes a keyframe: ORB-SLAM2's Tracking::NeedNewKeyFrame, RGB-D
/// branch. With n = inliers tracked in this frame and r = map points of the reference keyframe
/// observed by at least 2 keyframes (1 while the map has at most 2 keyframes; ORB-SLAM2 asks
/// for 3 and 2 observations, and counts each RGB-D observation twice):
///
///   close     = tracked close points < 100 and untracked close points > 70
///               ("close": depth below 3 m, ORB-SLAM2's bf * ThDepth / fx)
///   c1a       = frames since the last keyframe >= max_frames (30)
///   c1b       = frames since the last keyframe >= min_frames (0) and local mapping idle
///   c1c       = n < 0.25 r or close
///   c2        = (n < ratio r or close) and n > 15, ratio = 0.75 (0.4 while the map has one
///               keyframe)
///   insert    = (c1a or c1b or c1c) and c2
///
/// and never within max_frames frames of a relocalisation once the map has more than
/// max_frames keyframes. There is no local-mapping thread here, so "idle" is always true and
/// c1b only waits min_frames frames: the decision is c2's, as in ORB-SLAM2 whenever local
/// mapping keeps up.

#include "frontend/map/map_config.hpp"

#include <cstdint>
#include <vector>

namespace hbos::slam {

/// What the rule looks at, counted by the tracker.
struct KeyframeEvidence {
  int frames_since_keyframe = 0;
  int frames_since_relocalisation = 1 << 30;  ///< large when never relocalised
  int keyframes_in_map = 0;
  int tracked = 0;            ///< inliers in this frame
  int reference_tracked = 0;  ///< r above
  int tracked_close = 0;      ///< inliers with depth below close_depth_m
  int untracked_close = 0;    ///< keypoints with such depth but no map point
};

[[nodiscard]] bool need_keyframe(const KeyframeEvidence& e, const KeyframeConfig& config);

/// The keypoints a new keyframe makes map points from (Tracking::CreateNewKeyFrame, RGB-D, with
/// one departure): those with depth (`depth_m` > 0) and not `taken` (they observe a point),
/// nearest first: all closer than close_depth_m, then max_far_points of the farther ones (all, by
/// default), and at least min_new_points in all. ORB-SLAM2 stops at the near ones (or the
/// min_new_points nearest) and triangulates the far ones later in its local mapping thread, which
/// this tracker does not have.
[[nodiscard]] std::vector<int> select_new_points(const std::vector<float>& depth_m,
                                                 const std::vector<std::uint8_t>& taken,
                                                 const KeyframeConfig& config);

/// The keyframes that must observe a reference point for it to count in r: 2, or 1 while the
/// map has at most 2 keyframes.
[[nodiscard]] inline int reference_min_observations(int keyframes_in_map) {
  return keyframes_in_map <= 2 ? 1 : 2;
}

}  // namespace hbos::slam
