#include "frontend/map/noise_history.hpp"

#include <hbos/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace hbos::slam {

std::vector<double> noise_shares(const std::vector<PointNoise>& noise,
                                 const NoiseHistoryConfig& config) {
  hbos::detail::require(std::isfinite(config.ratio) && config.ratio >= 1.0,
                        "NoiseHistoryConfig ratio must be finite and >= 1, got ", config.ratio);
  hbos::detail::require(config.min_frames >= 1, "NoiseHistoryConfig min_frames must be >= 1, got ",
                        config.min_frames);
  hbos::detail::require(config.memory >= 0.0 && config.memory < 1.0,
                        "NoiseHistoryConfig memory must be in [0, 1), got ", config.memory);
  std::vector<double> shares(noise.size(), 0.0);
  std::vector<double> known;
  for (const PointNoise& n : noise)
    if (n.frames() >= config.min_frames) known.push_back(n.mean_square());
  // Too few points with a record to say what this frame's typical residual is.
  constexpr std::size_t kMinKnown = 10;
  if (known.size() < kMinKnown) return shares;
  const auto mid = known.begin() + static_cast<std::ptrdiff_t>(known.size() / 2);
  std::nth_element(known.begin(), mid, known.end());
  const double reference = config.ratio * *mid;
  if (!(reference > 0.0)) return shares;
  for (std::size_t i = 0; i < noise.size(); ++i) {
    if (noise[i].frames() < config.min_frames) continue;
    const double q = noise[i].mean_square();
    // A mean that overflowed is as far from the frame's noise as a record can say.
    shares[i] = std::isfinite(q) ? q / (q + reference) : 1.0;
  }
  return shares;
}

}  // namespace hbos::slam
