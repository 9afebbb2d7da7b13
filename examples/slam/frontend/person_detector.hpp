#pragma once
/// \file
/// The dynamic-object prior: Yolo-Fastest 1.1 "body" (a 1.2 MB Darknet person detector, public
/// domain) run with OpenCV's DNN module. It gives boxes, not silhouettes; the mask stage fills
/// them.

#include "frontend/config.hpp"

#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>

#include <string>
#include <vector>

namespace hbos::slam {

struct PersonBox {
  cv::Rect box;            ///< [px] clipped to the image
  float confidence = 0.f;  ///< the network's class score (OpenCV folds the objectness into it)
};

/// Not thread-safe (the network keeps state); one per thread.
class PersonDetector {
 public:
  /// Loads `yolo-fastest-1.1_body.cfg` and `.weights` from config.detector_dir. Throws
  /// hbos::InvalidArgument naming the file when it is missing or does not load.
  explicit PersonDetector(const MaskConfig& config);

  /// People in an 8-bit BGR image, after non-maximum suppression, highest confidence first.
  [[nodiscard]] std::vector<PersonBox> detect(const cv::Mat& bgr);

 private:
  cv::dnn::Net net_;
  std::vector<std::string> output_names_;
  float confidence_;
  float nms_;
  int input_px_;
};

}  // namespace hbos::slam
