#pragma once
/// \file
/// Local mapping's bundle adjustment, run when a keyframe joins the map: the new keyframe and
/// its most covisible neighbours move, every point they observe moves, and the other keyframes
/// observing those points hold the map in place (LocalMapping::Run ->
/// Optimizer::LocalBundleAdjustment in ORB-SLAM2). Observations the adjustment finds beyond the
/// chi^2 gates are erased from the map, as ORB-SLAM2 erases them.
///
/// Without it a point keeps the position one keyframe's depth and pose gave it: the depth's
/// noise and that keyframe's pose error stay in the point for as long as it is tracked.

#include "frontend/map/map.hpp"
#include "frontend/map/map_config.hpp"

#include <hbos/screening/pinhole.hpp>

namespace hbos::slam {

/// What one adjustment did.
struct LocalBundleReport {
  int moving_keyframes = 0;
  int fixed_keyframes = 0;
  int points = 0;
  int observations = 0;
  int outliers = 0;        ///< observations erased from the map
  bool discarded = false;  ///< a keyframe would have moved too far: the map was left as it was
  int iterations = 0;
  double initial_cost = 0.0;  ///< robust cost, whitened units (local_bundle_adjustment.hpp)
  double final_cost = 0.0;
};

/// Adjusts the local map around `keyframe_id` in place, on the points the screen has kept
/// often enough and does not distrust (`history`: ScreeningHistory::proven, distrusted). Does
/// nothing (and reports zeros) when there is nothing to adjust.
LocalBundleReport adjust_local_map(Map& map, int keyframe_id, const hbos::PinholeCamerad& camera,
                                   const LocalBundleConfig& config, const HistoryConfig& history);

}  // namespace hbos::slam
