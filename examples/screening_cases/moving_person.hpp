#pragma once
/// \file
/// A real person cut-out moving through the world while the camera moves: the cut-out is a
/// billboard whose anchor point moves at a constant world velocity; in each frame the anchor is
/// projected with the frame's ground-truth camera pose, the cut-out is scaled by the anchor's
/// depth (perspective) and pasted with sub-pixel placement. Its pixels' depths are the cut-out's
/// relative depth times the anchor's depth, so its back-projected points are where a sensor would
/// have put them. A person with zero velocity is a static billboard; its image motion is then the
/// camera's, so its matches' residuals measure only the compositing, not the motion.

#include "person_cutouts.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <hbos/screening/pinhole.hpp>
#include <opencv2/core.hpp>

#include <vector>

namespace hbos::cases {

/// Where a person is and how it moves. Frames: the first frame's camera (x right, y down,
/// z forward).
struct PersonMotion {
  char person = 'A';         ///< which SourcePerson
  double scale = 1.0;        ///< cut-out pixels per source pixel in the first frame
  double depth_m = 1.0;      ///< [m] the person's median depth in the first frame
  Eigen::Vector2d start_px;  ///< [px] where the cut-out's box centre lies in the first frame
  Eigen::Vector3d velocity_m_s = Eigen::Vector3d::Zero();  ///< [m/s] in the first camera's axes
};

/// Places persons into frames. `T_world_first` is the first frame's camera pose (T_world_camera).
class MovingPeople {
 public:
  /// Throws hbos::InvalidArgument when a motion names a person that is not in `people`, or has a
  /// scale or depth that is not finite and > 0.
  MovingPeople(const std::vector<SourcePerson>& people, std::vector<PersonMotion> motions,
               hbos::PinholeCamerad camera, const Eigen::Isometry3d& T_world_first,
               double first_stamp);

  /// Composites every person into `bgr` / `depth_m` of the frame at `stamp` whose camera pose is
  /// `T_world_camera`, nearest last (it occludes). Returns the label (CV_8U, 0 = background,
  /// k + 1 = the k-th motion's person, as drawn: an occluded pixel has the occluder's label).
  cv::Mat composite(double stamp, const Eigen::Isometry3d& T_world_camera, cv::Mat& bgr,
                    cv::Mat& depth_m) const;

 private:
  struct Placed {
    const SourcePerson* source = nullptr;
    PersonMotion motion;
    Eigen::Vector3d anchor_world;  ///< [m] at first_stamp
    Eigen::Vector3d velocity_world;
  };
  std::vector<Placed> placed_;
  hbos::PinholeCamerad camera_;
  double first_stamp_ = 0.0;
};

}  // namespace hbos::cases
