#pragma once
/// \file
/// The pinhole camera used to reproject map points for reprojection screening.
///
/// Projection of a point `p_c = (x, y, z)` given in the camera frame (z forward, x right, y down,
/// as OpenCV and ORB-SLAM use):
///
///     u = fx * x / z + cx,    v = fy * y / z + cy
///
/// No distortion: screening works on undistorted keypoints, as ORB-SLAM2's tracker does.
///
/// Threading: every type and function here is re-entrant.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "hbos/error.hpp"

namespace hbos {

/// Pinhole intrinsics in pixels. The defaults are ORB-SLAM2's TUM3.yaml (the TUM fr3 Kinect).
template <class Scalar>
struct PinholeCamera {
  Scalar fx = Scalar(535.4);  ///< focal length along x [px]
  Scalar fy = Scalar(539.2);  ///< focal length along y [px]
  Scalar cx = Scalar(320.1);  ///< principal point x [px]
  Scalar cy = Scalar(247.6);  ///< principal point y [px]

  /// Pixel of `p_c`, a point in this camera's frame with depth `p_c.z() > 0` [m].
  [[nodiscard]] Eigen::Matrix<Scalar, 2, 1> project(const Eigen::Matrix<Scalar, 3, 1>& p_c) const {
    const Scalar inv_z = Scalar(1) / p_c.z();
    return {fx * p_c.x() * inv_z + cx, fy * p_c.y() * inv_z + cy};
  }

  /// The camera-frame point at depth `z` [m] that projects to pixel `uv` (the inverse of project).
  [[nodiscard]] Eigen::Matrix<Scalar, 3, 1> back_project(const Eigen::Matrix<Scalar, 2, 1>& uv,
                                                         Scalar z) const {
    return {(uv.x() - cx) * z / fx, (uv.y() - cy) * z / fy, z};
  }
};

using PinholeCamerad = PinholeCamera<double>;
using PinholeCameraf = PinholeCamera<float>;

namespace detail {

template <class Scalar>
void validate(const PinholeCamera<Scalar>& camera) {
  require(std::isfinite(camera.fx) && camera.fx > Scalar(0),
          "PinholeCamera fx must be finite and > 0, got ", camera.fx);
  require(std::isfinite(camera.fy) && camera.fy > Scalar(0),
          "PinholeCamera fy must be finite and > 0, got ", camera.fy);
  require(std::isfinite(camera.cx), "PinholeCamera cx must be finite, got ", camera.cx);
  require(std::isfinite(camera.cy), "PinholeCamera cy must be finite, got ", camera.cy);
}

}  // namespace detail
}  // namespace hbos
