#pragma once
/// \file
/// Segmentation masks as a segmenter really gives them: named, seeded variants derived from the
/// perfect mask (object id != 0) and the object-id image.
///
/// Convention (DynaSLAM's: 0 = dynamic): 8-bit, 0 = dynamic, 255 = static (DynaSLAM's own files
/// use 1 for static; any non-zero value means static).

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace hbos::render {

/// Values in a mask image.
inline constexpr unsigned char kMaskDynamic = 0;
inline constexpr unsigned char kMaskStatic = 255;

/// The variant names, in output order.
const std::vector<std::string>& mask_variant_names();

/// What the variants need to know about the sequence; fixed once per sequence from the seed.
struct MaskPlan {
  std::uint64_t seed = 0;
  int frame_count = 0;
  std::vector<int> carried_ids;     ///< object ids of carried objects (object_unmasked drops them)
  int missed_person = 0;            ///< person_missed: this id is not masked ...
  int missed_first = 0;             ///< ... from this frame ...
  int missed_last = -1;             ///< ... to this one (inclusive)
  std::vector<int> missing_frames;  ///< missing: these frames have an all-static mask
  int erode_min_px = 3, erode_max_px = 6;     ///< [px] eroded: radius drawn per frame
  int dilate_min_px = 5, dilate_max_px = 12;  ///< [px] dilated: radius drawn per frame
  double missing_rate = 0.15;                 ///< share of frames without a mask

  /// Draws the missing frames, the missed person and their stretch (a quarter of the sequence,
  /// at least 15 frames) from `seed`.
  static MaskPlan make(std::uint64_t seed, int frame_count, int people,
                       std::vector<int> carried_ids);
};

/// The perfect mask of an object-id image: 0 where id != 0.
cv::Mat perfect_mask(const cv::Mat& object_id);

/// The mask of `variant` for `frame`. `ids` is this frame's object-id image, `previous_ids`
/// the previous frame's (empty for frame 0: delayed then gives an all-static mask, as a
/// segmenter with one frame of latency has nothing yet).
/// \throws std::invalid_argument for an unknown variant.
cv::Mat make_mask(const std::string& variant, const MaskPlan& plan, int frame, const cv::Mat& ids,
                  const cv::Mat& previous_ids);

}  // namespace hbos::render
