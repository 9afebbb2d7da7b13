#pragma once
/// \file
/// A rendered sequence: scenario + seed -> per frame the camera pose, the sensor's colour and
/// depth images, and the ground truth (noise-free depth, world positions, object ids).
///
/// Frame i is a function of (scenario, seed, i) only: frames can be rendered in any order.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "render/camera.hpp"
#include "render/gl_renderer.hpp"
#include "render/kinect.hpp"
#include "render/masks.hpp"
#include "render/person.hpp"
#include "render/room.hpp"
#include "render/scenario.hpp"
#include "render/trajectory.hpp"

namespace hbos::render {

/// The renderer's version (written to scenario.json; bump it when the bytes change).
inline constexpr const char* kRendererVersion = "1.0.0";

/// What to render.
struct SequenceOptions {
  std::string scenario = "walking_xyz";  ///< one of scenario_names()
  std::uint64_t seed = 1;
  int frames = 0;                                       ///< 0 = the whole ground-truth trajectory
  int people = -1;                                      ///< 1..3, -1 = the scenario's default
  double rate = 30.0;                                   ///< [Hz] frame rate
  std::filesystem::path data_dir = default_data_dir();  ///< textures/, trajectories/
  KinectModel kinect;                                   ///< sensor model
  Intrinsics K;                                         ///< camera (TUM fr3)
};

/// One frame.
struct Frame {
  int index = 0;
  double stamp = 0.0;  ///< [s] TUM time stamp
  Pose pose;           ///< camera-to-world (room frame)
  RenderedView truth;  ///< noise-free render (depth in metres, ids, world points)
  cv::Mat rgb;         ///< CV_8UC3 BGR, as the sensor gives it
  cv::Mat depth;       ///< CV_16U, 5000 units/m, 0 = no return
};

/// Renders the frames of one scenario. Not thread-safe (owns an OpenGL context).
class SequenceRenderer {
 public:
  /// \throws UsageError for a bad scenario or count, InputError for missing data files,
  /// std::runtime_error if OpenGL cannot be set up.
  explicit SequenceRenderer(const SequenceOptions& options);
  ~SequenceRenderer();

  int frame_count() const { return static_cast<int>(poses_.size()); }
  const std::vector<StampedPose>& poses() const { return poses_; }
  const Scenario& scenario() const { return scenario_; }
  const SequenceOptions& options() const { return options_; }
  /// The offset from the mocap frame of the ground truth to the room frame.
  const Pose& room_from_mocap() const { return room_from_mocap_; }
  /// Object ids of the carried objects (people are 1..k, objects k+1..).
  const std::vector<int>& carried_ids() const { return carried_ids_; }
  const MaskPlan& mask_plan() const { return mask_plan_; }
  std::string gl_name() const { return gl_->gl_renderer_name(); }

  /// Renders frame `i` (0 <= i < frame_count()).
  Frame render(int i);
  /// Only the noise-free render of frame `i` (no sensor model): for tests and tools.
  RenderedView render_truth(int i);

 private:
  std::vector<DrawItem> items_at(double t) const;

  SequenceOptions options_;
  Scenario scenario_;
  std::vector<StampedPose> poses_;
  Pose room_from_mocap_ = Pose::Identity();
  std::unique_ptr<GlRenderer> gl_;
  std::vector<DrawItem> room_items_;
  std::vector<PersonModel> people_;
  std::vector<Timeline> timelines_;
  std::vector<int> carried_ids_;
  std::vector<int> carried_by_;  // person index per carried id, or -1
  MaskPlan mask_plan_;
};

}  // namespace hbos::render
