#pragma once
/// \file
/// The pinhole camera of the rendered sequences: TUM fr3's Kinect colour camera.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace hbos::render {

/// Pinhole intrinsics, OpenCV/TUM convention: pixel (u, v) = (fx X/Z + cx, fy Y/Z + cy) with the
/// centre of the top-left pixel at (0, 0); camera frame x right, y down, z forward.
struct Intrinsics {
  double fx = 535.4;  ///< [px] TUM fr3 (Sturm et al. 2012, "ROS default" fr3 calibration)
  double fy = 539.2;  ///< [px]
  double cx = 320.1;  ///< [px]
  double cy = 247.6;  ///< [px]
  int width = 640;    ///< [px]
  int height = 480;   ///< [px]
};

/// A camera pose: camera-to-world (TUM groundtruth.txt convention), metres.
using Pose = Eigen::Isometry3d;

}  // namespace hbos::render
