#pragma once
/// \file
/// The real people of the TUM fr3/walking_xyz frame in ../shared: DynaSLAM's person mask split
/// into its connected components, each cut out with its colour and depth, left to right.

#include "frontend/person_scenario.hpp"

#include <string>
#include <vector>

namespace hbos::cases {

/// One person of the source frame.
struct SourcePerson {
  char id = 'A';                 ///< 'A' = leftmost person, 'B' = the next, ...
  cv::Rect box;                  ///< [px] bounding box in the source frame
  int pixels = 0;                ///< person pixels
  double median_depth_m = 0.0;   ///< [m] in the source frame
  hbos::slam::PersonCutout cut;  ///< colour, mask (255 = this person only), relative depth
};

/// Reads `rgb/<stamp>.png`, `mask/<stamp>.png` (DynaSLAM: 0 = person) and `depth/<depth
/// stamp>.png` of `fr3_folder` and returns every connected person region of at least
/// `min_pixels` pixels (8-connectivity), sorted by the box's left edge. Throws
/// hbos::InvalidArgument naming the file when an image is missing or of the wrong type, or when
/// no person is found.
[[nodiscard]] std::vector<SourcePerson> cut_people(const std::string& fr3_folder,
                                                   int min_pixels = 1000);

}  // namespace hbos::cases
