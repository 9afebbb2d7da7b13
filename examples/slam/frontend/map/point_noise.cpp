#include "frontend/map/point_noise.hpp"

#include <hbos/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace hbos::slam {

double median_mean_square(const std::vector<PointNoise>& noise, int min_frames,
                          const std::vector<std::uint8_t>* use) {
  std::vector<double> known;
  for (std::size_t i = 0; i < noise.size(); ++i)
    if ((use == nullptr || (*use)[i] != 0) && noise[i].frames() >= min_frames)
      known.push_back(noise[i].mean_square());
  constexpr std::size_t kMinKnown = 10;
  if (known.size() < kMinKnown) return 0.0;
  const auto mid = known.begin() + static_cast<std::ptrdiff_t>(known.size() / 2);
  std::nth_element(known.begin(), mid, known.end());
  return *mid;
}

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
  const double reference = config.tolerance * median_mean_square(noise, config.min_frames, &use);
  if (!(reference > 0.0)) return;  // too few used points with a record, or a median of 0
  for (std::size_t i = 0; i < noise.size(); ++i) {
    const double q = noise[i].mean_square();
    if (noise[i].frames() >= config.min_frames && q > reference)
      sigma[i] *= std::sqrt(q / reference);
  }
}

}  // namespace hbos::slam
