#pragma once
/// \file
/// The labelled dynamic scenario: a real person, cut out of a TUM fr3/walking_xyz frame, pasted
/// into every frame of a static sequence. Where the cut-out's mask is set, colour and depth are
/// overwritten, so the ground truth stays the static sequence's and every feature on the person
/// is known to be dynamic: the returned mask is the label.

#include "frontend/config.hpp"

#include <opencv2/core.hpp>

#include <string>

namespace hbos::slam {

/// A person cut-out: colour, mask (255 = person) and depth, all the same size.
struct PersonCutout {
  cv::Mat bgr;             ///< 8-bit BGR
  cv::Mat mask;            ///< CV_8U, 255 on the person
  cv::Mat relative_depth;  ///< CV_32F, depth / median depth over the person; 0 = no measurement
};

/// Reads `rgb.png`, `mask.png` and `depth.png` (16-bit, 5000 per metre) of `folder`. Throws
/// hbos::InvalidArgument naming the file when one is missing, of the wrong type or size, or the
/// mask has no person pixel with depth.
[[nodiscard]] PersonCutout load_person_cutout(const std::string& folder);

/// Composites the person into frames: in frame i its left edge is at start_x + i * speed, its
/// bottom on the image's bottom row, its median depth at `depth_m`.
class PersonCompositor {
 public:
  PersonCompositor(PersonCutout cutout, ScenarioConfig config);

  /// Top-left corner of the cut-out in frame `index` [px] (may lie partly outside the image).
  [[nodiscard]] cv::Point position(int index, cv::Size image) const;

  /// Overwrites `bgr` and `depth_m` where the person is and returns the label mask (CV_8U,
  /// 255 = person, the image's size).
  cv::Mat composite(int index, cv::Mat& bgr, cv::Mat& depth_m) const;

 private:
  PersonCutout cutout_;
  ScenarioConfig config_;
};

}  // namespace hbos::slam
