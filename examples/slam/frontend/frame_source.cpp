#include "frontend/frame_source.hpp"

#include <chrono>
#include <utility>

namespace hbos::slam {

FrameSource::FrameSource(RgbdSequence sequence, double depth_factor, const ScenarioConfig& scenario,
                         const MaskConfig& mask)
    : sequence_(std::move(sequence)), depth_factor_(depth_factor), masker_(mask) {
  if (scenario.add_person) compositor_.emplace(load_person_cutout(scenario.person_dir), scenario);
  if (mask.source == MaskSource::kFiles) {
    mask_files_.emplace(sequence_, mask.files_dir, mask.files_convention,
                        mask.files_max_difference);
  }
  const std::string objects =
      scenario.objects_dir.empty() ? default_objects_dir(sequence_) : scenario.objects_dir;
  if (!scenario.add_person && !objects.empty()) {
    labels_.emplace(sequence_, objects, mask.files_max_difference);
  }
}

Frame FrameSource::frame(int index) {
  RgbdImages images = read_frame_images(sequence_, index, depth_factor_);
  Frame f;
  f.index = index;
  f.stamp = sequence_.frames[static_cast<std::size_t>(index)].rgb.stamp;
  f.bgr = std::move(images.bgr);
  f.depth_m = std::move(images.depth_m);
  if (compositor_) f.person_label = compositor_->composite(index, f.bgr, f.depth_m);
  if (labels_) f.person_label = labels_->label(index);
  const auto start = std::chrono::steady_clock::now();
  f.mask = mask_files_ ? mask_files_->mask(index) : masker_.mask(index, f.bgr, f.person_label);
  f.mask_us =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  f.detections = masker_.last_boxes();
  return f;
}

}  // namespace hbos::slam
