#pragma once
/// \file
/// Keypoints spread over the image, as ORB-SLAM2's extractor spreads them (its quadtree keeps the
/// best corner of each node). cv::ORB keeps the strongest corners of the whole frame, so a
/// textured person near the camera can take most of them. Here a larger pool is detected and,
/// per pyramid level, each image cell yields its best corner before any cell yields its second.
/// Off by default: it trades the strongest corners of textured regions for weaker ones elsewhere,
/// and that cost more than it gained on some camera paths (docs/results.md, "Keypoints spread
/// over the image").

#include <opencv2/core.hpp>

#include <vector>

namespace hbos::slam {

/// `target` keypoints out of `pool` (all when it holds fewer). Each level keeps its share of the
/// pool (so the scale distribution cv::ORB chose stays), and within a level the keypoints are
/// taken round by round: in round r the r-th strongest of every `cell_px` cell that has one,
/// strongest first. `cell_px` > 0. The order of the result is the pool's.
[[nodiscard]] std::vector<cv::KeyPoint> spread_keypoints(const std::vector<cv::KeyPoint>& pool,
                                                         int target, float cell_px);

}  // namespace hbos::slam
