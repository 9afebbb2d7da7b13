#include "frontend/map/noise_history.hpp"

#include <hbos/error.hpp>

#include <cmath>

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
  const double reference = config.ratio * median_mean_square(noise, config.min_frames);
  if (!(reference > 0.0)) return shares;  // too few points with a record, or a median of 0
  for (std::size_t i = 0; i < noise.size(); ++i) {
    if (noise[i].frames() < config.min_frames) continue;
    const double q = noise[i].mean_square();
    // A mean that overflowed is as far from the frame's noise as a record can say.
    shares[i] = std::isfinite(q) ? q / (q + reference) : 1.0;
  }
  return shares;
}

}  // namespace hbos::slam
