#pragma once
/// \file
/// The RGB-D camera: pinhole intrinsics, the Brown-Conrady distortion of the TUM fr1 Kinect, and
/// the depth scale. Keypoints are detected on the distorted image and undistorted before any
/// geometry, as ORB-SLAM2 does; depth images are registered to the (distorted) colour image.

#include <hbos/screening/pinhole.hpp>

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace hbos::slam {

struct CameraModel {
  std::string name;  ///< preset name or file, for reports
  double fx = 0.0;   ///< [px]
  double fy = 0.0;   ///< [px]
  double cx = 0.0;   ///< [px]
  double cy = 0.0;   ///< [px]
  double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0,
         k3 = 0.0;               ///< OpenCV's distortion order k1 k2 p1 p2 k3
  double depth_factor = 5000.0;  ///< depth image units per metre (TUM: 5000)

  [[nodiscard]] bool has_distortion() const;
  [[nodiscard]] cv::Matx33d camera_matrix() const;
  /// (k1, k2, p1, p2, k3) as OpenCV expects them.
  [[nodiscard]] cv::Mat distortion_coefficients() const;
  [[nodiscard]] hbos::PinholeCamerad pinhole() const;
};

/// `tum1` (fr1 Kinect, with distortion) or `tum3` (fr3, none), as ORB-SLAM2's TUM1/TUM3.yaml.
/// Throws hbos::InvalidArgument for any other name.
[[nodiscard]] CameraModel camera_preset(const std::string& name);

/// A preset name, or a file: `.json` ({"fx": ..., ...}) or `.yaml`/`.yml` (`key: value` lines,
/// e.g. ORB-SLAM2's settings file). Keys fx, fy, cx, cy are required; k1, k2, p1, p2, k3
/// (default 0) and depth_factor (default 5000) are optional; a `Camera.` prefix is accepted and
/// ORB-SLAM2's `DepthMapFactor` means depth_factor. Other keys are ignored, so an ORB-SLAM2
/// settings file loads as is. Throws hbos::InvalidArgument naming file:line and the field.
///
/// Legal ranges (anything else is an error naming the field and the value): fx, fy in
/// [1, 1e6] px (below 1 px the field of view exceeds 180 degrees; 1e6 px is a 0.04 degree lens on
/// a 640-px image); cx, cy finite (checked against the image by check_camera_fits_image);
/// k1, k2, p1, p2, k3 finite with |k| <= 1000; depth_factor in (0, 1e9] (raw depth units per
/// metre; TUM: 5000). A number beyond the range of a double (`517.3e6408`) is an error too.
[[nodiscard]] CameraModel load_camera(const std::string& preset_or_path);

/// Throws hbos::InvalidArgument unless the principal point (cx, cy) lies inside a
/// `width` x `height` image ([0, width] x [0, height] px); `image` names it in the message.
void check_camera_fits_image(const CameraModel& camera, int width, int height,
                             const std::string& image);

/// Undistorted pixel positions of `distorted` pixels (identity without distortion).
[[nodiscard]] std::vector<cv::Point2f> undistort_pixels(const CameraModel& camera,
                                                        const std::vector<cv::Point2f>& distorted);

}  // namespace hbos::slam
