#pragma once
/// \file
/// Frames as the tracker sees them: read from the sequence, the person composited in (dynamic
/// scenario), and the dynamic-object mask computed.

#include "frontend/config.hpp"
#include "frontend/dataset.hpp"
#include "frontend/frame.hpp"
#include "frontend/mask_files.hpp"
#include "frontend/person_mask.hpp"
#include "frontend/person_scenario.hpp"

#include <optional>

namespace hbos::slam {

class FrameSource {
 public:
  /// Loads the person cut-out (scenario.add_person) and the detector (mask.source == kDetector);
  /// resolves and checks every frame's mask file (kFiles) and, without a composited person, the
  /// ground-truth object ids (scenario.objects_dir or `<dataset>/objects`); throws
  /// hbos::InvalidArgument when any of them cannot be loaded or a file is missing or misfit.
  FrameSource(RgbdSequence sequence, double depth_factor, const ScenarioConfig& scenario,
              const MaskConfig& mask);

  [[nodiscard]] int size() const { return static_cast<int>(sequence_.size()); }
  [[nodiscard]] const RgbdSequence& sequence() const { return sequence_; }

  /// Frame `index` (0 <= index < size()).
  [[nodiscard]] Frame frame(int index);

 private:
  RgbdSequence sequence_;
  double depth_factor_;
  std::optional<PersonCompositor> compositor_;
  PersonMasker masker_;
  std::optional<MaskFiles> mask_files_;  ///< mask.source == kFiles
  std::optional<ObjectLabels> labels_;   ///< ground truth from object-id images
};

}  // namespace hbos::slam
