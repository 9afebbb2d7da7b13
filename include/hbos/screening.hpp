#pragma once
/// \file
/// Reprojection-residual screening in one include: a frame's matches (screening/matches.hpp),
/// the dominant residual field and its rigid refit (screening/residual_field.hpp,
/// screening/rigid_field.hpp), the strategies
/// (screening/strategies.hpp), the screen (screening/screen.hpp), the pinhole model and the
/// Gauss-Newton pose refit (screening/pinhole.hpp, screening/pose_refinement.hpp), the leverage of
/// a group of matches on the pose (screening/pose_leverage.hpp), and the conveniences for callers
/// that hold 3-D map points and a pose (screening/projection.hpp).
/// Eigen only. The OpenCV adapter (hbos/screening/opencv.hpp) is deliberately not included:
/// include it yourself where OpenCV is available.
///
/// Where it goes in an ORB-SLAM2-style tracker: after the rough pose (motion model or reference
/// keyframe), before Optimizer::PoseOptimization; see docs/screening.md for the snippet.

#include "hbos/screening/matches.hpp"
#include "hbos/screening/pinhole.hpp"
#include "hbos/screening/pose_leverage.hpp"
#include "hbos/screening/pose_refinement.hpp"
#include "hbos/screening/projection.hpp"
#include "hbos/screening/residual_field.hpp"
#include "hbos/screening/rigid_field.hpp"
#include "hbos/screening/screen.hpp"
#include "hbos/screening/strategies.hpp"
