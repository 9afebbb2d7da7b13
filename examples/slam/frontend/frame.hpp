#pragma once
/// \file
/// What the tracker consumes per frame.

#include "frontend/person_detector.hpp"

#include <opencv2/core.hpp>

#include <vector>

namespace hbos::slam {

struct Frame {
  int index = 0;       ///< position in the sequence
  double stamp = 0.0;  ///< [s] the colour image's stamp
  cv::Mat bgr;         ///< 8-bit colour (with the person composited in the dynamic scenario)
  cv::Mat depth_m;     ///< CV_32F [m], 0 = no measurement
  cv::Mat mask;        ///< CV_8U, 255 = dynamic-object mask: no features are extracted there
  /// CV_8U, 255 = the composited person (ground-truth label); empty in the static scenario.
  /// Only the statistics read it, never the pipeline.
  cv::Mat person_label;
  std::vector<PersonBox> detections;  ///< the detector's boxes (detector mask only)
  double mask_us = 0.0;  ///< [us] time to compute `mask` (the detector's, for the detector mask)
};

}  // namespace hbos::slam
