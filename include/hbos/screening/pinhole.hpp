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

  /// The rows d(u, v) / d(motion) of the pixel `uv` of a point with inverse depth
  /// `inverse_depth` [1/m] (0: a point at infinity) under a small rigid motion of the scene in
  /// this camera's frame, motion = (t [m], w [rad]): the point P moves to P + t + w x P. To first
  /// order the pixel moves by `ju . motion` along u and `jv . motion` along v.
  void motion_jacobian(const Eigen::Matrix<Scalar, 2, 1>& uv, Scalar inverse_depth,
                       Eigen::Matrix<Scalar, 6, 1>& ju, Eigen::Matrix<Scalar, 6, 1>& jv) const {
    const Scalar x = (uv.x() - cx) / fx, y = (uv.y() - cy) / fy, q = inverse_depth;
    ju << fx * q, Scalar(0), -fx * x * q, -fx * x * y, fx * (Scalar(1) + x * x), -fx * y;
    jv << Scalar(0), fy * q, -fy * y * q, -fy * (Scalar(1) + y * y), fy * x * y, fy * x;
  }

  /// The first-order pixel shift of `uv` (inverse depth `inverse_depth`) under `motion`
  /// (motion_jacobian).
  [[nodiscard]] Eigen::Matrix<Scalar, 2, 1> pixel_motion(
      const Eigen::Matrix<Scalar, 2, 1>& uv, Scalar inverse_depth,
      const Eigen::Matrix<Scalar, 6, 1>& motion) const {
    Eigen::Matrix<Scalar, 6, 1> ju, jv;
    motion_jacobian(uv, inverse_depth, ju, jv);
    return {ju.dot(motion), jv.dot(motion)};
  }

  /// The same intrinsics in another scalar type (each one converted with static_cast).
  template <class Other>
  [[nodiscard]] PinholeCamera<Other> cast() const {
    return {static_cast<Other>(fx), static_cast<Other>(fy), static_cast<Other>(cx),
            static_cast<Other>(cy)};
  }

  /// Exact equality of the four intrinsics: whether a cached value built for one camera still
  /// holds for another.
  [[nodiscard]] friend bool operator==(const PinholeCamera& a, const PinholeCamera& b) {
    return a.fx == b.fx && a.fy == b.fy && a.cx == b.cx && a.cy == b.cy;
  }
  [[nodiscard]] friend bool operator!=(const PinholeCamera& a, const PinholeCamera& b) {
    return !(a == b);
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
