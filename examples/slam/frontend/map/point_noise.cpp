#include "frontend/map/point_noise.hpp"

#include <hbos/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace hbos::slam {

void widen_by_point_noise(const std::vector<PointNoise>& noise,
                          const std::vector<std::uint8_t>& use, const PointNoiseConfig& config,
                          std::vector<double>& sigma) {
  hbos::detail::require(noise.size() == sigma.size() && use.size() == sigma.size(),
                        "widen_by_point_noise: ", noise.size(), " noise records, ", use.size(),
                        " use flags and ", sigma.size(), " sigmas; one of each per match expected");
  hbos::detail::require(std::isfinite(config.tolerance) && config.tolerance >= 1.0,
                        "PointNoiseConfig tolerance must be finite and >= 1, got ",
                        config.tolerance);
  hbos::detail::require(config.min_frames >= 1, "PointNoiseConfig min_frames must be >= 1, got ",
                        config.min_frames);
  hbos::detail::require(config.memory >= 0.0 && config.memory < 1.0,
                        "PointNoiseConfig memory must be in [0, 1), got ", config.memory);
  std::vector<double> known;  // the used points' own noise, where they have shown it
  for (std::size_t i = 0; i < noise.size(); ++i)
    if (use[i] != 0 && noise[i].frames() >= config.min_frames)
      known.push_back(noise[i].mean_square());
  // Too few points with a history to say what this frame's noise is: every point as it comes.
  constexpr std::size_t kMinKnown = 10;
  if (known.size() < kMinKnown) return;
  const auto mid = known.begin() + static_cast<std::ptrdiff_t>(known.size() / 2);
  std::nth_element(known.begin(), mid, known.end());
  const double reference = config.tolerance * *mid;
  if (!(reference > 0.0)) return;
  for (std::size_t i = 0; i < noise.size(); ++i) {
    const double q = noise[i].mean_square();
    if (noise[i].frames() >= config.min_frames && q > reference)
      sigma[i] *= std::sqrt(q / reference);
  }
}

}  // namespace hbos::slam
