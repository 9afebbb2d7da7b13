#include "frontend/mask_distance.hpp"

#include <hbos/screening/strategies.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <variant>

namespace hbos::slam {

double mask_evidence_reach_px(const Config& config) {
  if (!config.screen.mask_evidence || config.mask.source == MaskSource::kNone ||
      !config.screen.screen.has_value())
    return 0.0;
  const auto* hbos_screen = std::get_if<hbos::HbosScreen>(&config.screen.screen->strategy);
  if (hbos_screen == nullptr || !hbos_screen->gate.enabled || !hbos_screen->mask.enabled)
    return 0.0;
  return hbos_screen->mask.radius_px;
}

MaskDistance::MaskDistance(const cv::Mat& mask, double reach_px)
    : reach_px_(reach_px), reach_(static_cast<int>(std::floor(reach_px))) {
  CV_Assert(mask.empty() || mask.type() == CV_8UC1);
  CV_Assert(reach_px >= 0.0 && std::isfinite(reach_px));
  if (mask.empty()) return;
  cv::Mat occupied((mask.rows + kBlock - 1) / kBlock, (mask.cols + kBlock - 1) / kBlock, CV_8U,
                   cv::Scalar(0));
  bool any = false;
  for (int v = 0; v < mask.rows; ++v) {
    const auto* row = mask.ptr<std::uint8_t>(v);
    auto* blocks = occupied.ptr<std::uint8_t>(v / kBlock);
    for (int b = 0; b < occupied.cols; ++b) {
      const int u0 = b * kBlock, u1 = std::min(mask.cols, u0 + kBlock);
      // Whether any byte of the block's run is set: OR-ed eight bytes at a time.
      std::uint64_t bits = 0;
      int u = u0;
      for (; u + 8 <= u1; u += 8) {
        std::uint64_t word = 0;
        std::memcpy(&word, row + u, sizeof word);
        bits |= word;
      }
      for (; u < u1; ++u) bits |= row[u];
      if (bits != 0) {
        blocks[b] = 1;
        any = true;
      }
    }
  }
  if (!any) return;
  mask_ = mask;
  occupied_ = occupied;
}

double MaskDistance::at(const cv::Point2f& pixel) const {
  constexpr double kFar = std::numeric_limits<double>::infinity();
  if (mask_.empty()) return kFar;
  const int x = std::clamp(static_cast<int>(std::lround(pixel.x)), 0, mask_.cols - 1);
  const int y = std::clamp(static_cast<int>(std::lround(pixel.y)), 0, mask_.rows - 1);
  long best = std::numeric_limits<long>::max();
  const int x0 = std::max(0, x - reach_), x1 = std::min(mask_.cols - 1, x + reach_);
  const int y0 = std::max(0, y - reach_), y1 = std::min(mask_.rows - 1, y + reach_);
  for (int bv = y0 / kBlock; bv <= y1 / kBlock; ++bv) {
    for (int bu = x0 / kBlock; bu <= x1 / kBlock; ++bu) {
      if (occupied_.at<std::uint8_t>(bv, bu) == 0) continue;
      // The part of the square inside this block.
      const int u0 = std::max(x0, bu * kBlock), u1 = std::min(x1, bu * kBlock + kBlock - 1);
      const int v0 = std::max(y0, bv * kBlock), v1 = std::min(y1, bv * kBlock + kBlock - 1);
      for (int v = v0; v <= v1; ++v) {
        const auto* row = mask_.ptr<std::uint8_t>(v);
        const long dv2 = static_cast<long>(v - y) * (v - y);
        for (int u = u0; u <= u1; ++u) {
          if (row[u] == 0) continue;
          best = std::min(best, dv2 + static_cast<long>(u - x) * (u - x));
        }
      }
    }
  }
  const double d = std::sqrt(static_cast<double>(best));
  return best != std::numeric_limits<long>::max() && d <= reach_px_ ? d : kFar;
}

}  // namespace hbos::slam
