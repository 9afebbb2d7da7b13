#pragma once
/// \file
/// The camera paths: real TUM fr3 ground truth, resampled to the 30 Hz frame clock.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/camera.hpp"

namespace hbos::render {

/// A trajectory or data file was missing or malformed; `what()` names file, line and field.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One timed pose.
struct StampedPose {
  double stamp = 0.0;  ///< [s] TUM time stamp
  Pose pose = Pose::Identity();
};

/// Reads a TUM trajectory (`stamp tx ty tz qx qy qz qw`, `#` comments). Stamps must not decrease
/// (one duplicated stamp, as in fr3/walking_static, is tolerated: the later line is dropped).
/// \throws InputError naming file, line and field.
std::vector<StampedPose> read_tum_trajectory(const std::filesystem::path& file);

/// Resamples at `rate` Hz from the first stamp: position linearly, rotation by slerp between the
/// two ground-truth poses around each frame time. Covers the whole ground truth. If `max_frames`
/// > 0 only that many frames are produced.
std::vector<StampedPose> resample(const std::vector<StampedPose>& gt, double rate, int max_frames);

/// The rigid offset that puts a ground-truth path into the room: a yaw about the vertical and a
/// horizontal shift (the mocap z axis is up and its z = 0 is close to the floor, so heights are
/// kept). The yaw turns the horizontal direction from the mean camera to the point the camera
/// looks at most (least-squares meeting point of the optical axes, pulled towards 2 m ahead of
/// the mean camera when the axes are nearly parallel) onto +y; the shift puts the mean camera at
/// `camera_xy` [m].
Pose room_offset(const std::vector<StampedPose>& path, const Eigen::Vector2d& camera_xy);

}  // namespace hbos::render
