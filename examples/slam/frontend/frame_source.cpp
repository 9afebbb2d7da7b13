#include "frontend/frame_source.hpp"

#include <chrono>
#include <utility>

namespace hbos::slam {

FrameSource::FrameSource(RgbdSequence sequence, double depth_factor, const ScenarioConfig& scenario,
                         const MaskConfig& mask)
    : sequence_(std::move(sequence)), depth_factor_(depth_factor), masker_(mask) {
  if (scenario.add_person) compositor_.emplace(load_person_cutout(scenario.person_dir), scenario);
}

Frame FrameSource::frame(int index) {
  RgbdImages images = read_frame_images(sequence_, index, depth_factor_);
  Frame f;
  f.index = index;
  f.stamp = sequence_.frames[static_cast<std::size_t>(index)].rgb.stamp;
  f.bgr = std::move(images.bgr);
  f.depth_m = std::move(images.depth_m);
  if (compositor_) f.person_label = compositor_->composite(index, f.bgr, f.depth_m);
  const auto start = std::chrono::steady_clock::now();
  f.mask = masker_.mask(index, f.bgr, f.person_label);
  f.mask_us =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  f.detections = masker_.last_boxes();
  return f;
}

}  // namespace hbos::slam
