#include "render/sequence.hpp"

namespace hbos::render {

SequenceRenderer::SequenceRenderer(const SequenceOptions& o) : options_(o) {
  if (o.frames < 0)
    throw UsageError("--frames must be >= 0 (got " + std::to_string(o.frames) + ")");
  scenario_ = make_scenario(o.scenario, o.seed, o.people);
  const auto gt = read_tum_trajectory(o.data_dir / "trajectories" / scenario_.trajectory_file);
  // The room offset comes from the whole path, so a short run sees the same room as a full one.
  const auto full = resample(gt, o.rate, 0);
  // The mean camera stands 2.3 m in front of the desk centre, as the fr3 camera does in front of
  // its desk, looking along +y at the desk and the people behind it.
  room_from_mocap_ = room_offset(full, Eigen::Vector2d(0.0, -2.3));
  poses_ = o.frames > 0 ? resample(gt, o.rate, o.frames) : full;
  for (auto& p : poses_) p.pose = room_from_mocap_ * p.pose;

  gl_ = std::make_unique<GlRenderer>(o.K);
  const TextureLibrary tex(o.data_dir);
  room_items_ = build_room(*gl_, tex, RoomLayout{});
  const int k = static_cast<int>(scenario_.people.size());
  for (int i = 0; i < k; ++i) {
    const PersonSpec& p = scenario_.people[static_cast<std::size_t>(i)];
    people_.emplace_back(*gl_, tex, p.look, p.height_scale);
    timelines_.emplace_back(p.start, p.start_yaw, p.start_seated, p.actions, p.speed, 2.5,
                            p.start_fraction);
    if (p.carries) {
      carried_ids_.push_back(k + 1 + static_cast<int>(carried_by_.size()));
      carried_by_.push_back(i);
    }
  }
  mask_plan_ = MaskPlan::make(o.seed, frame_count(), k, carried_ids_);
}

SequenceRenderer::~SequenceRenderer() = default;

std::vector<DrawItem> SequenceRenderer::items_at(double t) const {
  std::vector<DrawItem> items = room_items_;
  for (std::size_t i = 0; i < people_.size(); ++i) {
    int carried = 0;
    for (std::size_t c = 0; c < carried_by_.size(); ++c) {
      if (carried_by_[c] == static_cast<int>(i)) carried = carried_ids_[c];
    }
    people_[i].draw(timelines_[i].at(t), static_cast<int>(i) + 1, carried, items);
  }
  return items;
}

RenderedView SequenceRenderer::render_truth(int i) {
  const StampedPose& p = poses_.at(static_cast<std::size_t>(i));
  const double t = p.stamp - poses_.front().stamp;
  return gl_->render(p.pose, items_at(t));
}

Frame SequenceRenderer::render(int i) {
  Frame f;
  f.index = i;
  f.stamp = poses_.at(static_cast<std::size_t>(i)).stamp;
  f.pose = poses_[static_cast<std::size_t>(i)].pose;
  f.truth = render_truth(i);
  const auto idx = static_cast<std::uint64_t>(i);
  f.depth = kinect_depth(f.truth, options_.K, options_.kinect, options_.seed, idx);
  f.rgb = kinect_rgb(f.truth, options_.kinect, options_.seed, idx);
  return f;
}

}  // namespace hbos::render
