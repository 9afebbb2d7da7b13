#include "frontend/map/map_point.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace hbos::slam {

namespace {

int popcount64(std::uint64_t v) { return __builtin_popcountll(v); }

}  // namespace

int hamming(const Descriptor& a, const std::uint8_t* row) {
  int bits = 0;
  for (std::size_t w = 0; w < 4; ++w) {
    std::uint64_t x = 0, y = 0;
    std::memcpy(&x, a.data() + 8 * w, 8);
    std::memcpy(&y, row + 8 * w, 8);
    bits += popcount64(x ^ y);
  }
  return bits;
}

int hamming(const Descriptor& a, const Descriptor& b) { return hamming(a, b.data()); }

Descriptor descriptor_of(const std::uint8_t* row) {
  Descriptor d;
  std::memcpy(d.data(), row, d.size());
  return d;
}

int MapPoint::predict_octave(double distance_m, float scale_factor, int levels) const {
  if (!(distance_m > 0.0)) return 0;
  const double ratio = static_cast<double>(max_distance_m) / distance_m;
  const int octave =
      static_cast<int>(std::ceil(std::log(ratio) / std::log(static_cast<double>(scale_factor))));
  return std::clamp(octave, 0, levels - 1);
}

}  // namespace hbos::slam
