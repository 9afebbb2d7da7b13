#pragma once
/// \file
/// A small counter-based random source whose bytes are the same on every platform and standard
/// library (std::normal_distribution is implementation-defined, so it is not used): the renderer's
/// output must be a function of (scenario, seed) only.

#include <cmath>
#include <cstdint>
#include <vector>

namespace hbos::render {

/// SplitMix64 (Steele, Lea & Flood 2014): one 64-bit state, full period, good enough to seed and
/// to draw noise. Draws are reproducible bit for bit.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}

  /// A stream for one purpose and one frame: streams with different (seed, stream, index) are
  /// independent, so adding a draw in one place never shifts the noise anywhere else.
  static Rng stream(std::uint64_t seed, std::uint64_t stream_id, std::uint64_t index = 0) {
    Rng r(seed ^ 0x9E3779B97F4A7C15ULL);
    r.state_ ^= r.next() + stream_id * 0xBF58476D1CE4E5B9ULL;
    r.state_ ^= r.next() + index * 0x94D049BB133111EBULL;
    r.next();
    return r;
  }

  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }

  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [0, n) (n > 0).
  std::uint64_t below(std::uint64_t n) { return next() % n; }

  /// Four standard normal draws from one 64-bit draw, by table look-up of 16-bit quantiles (the
  /// per-pixel sensor noise needs millions per frame; exact tails beyond |x| ~ 4.3 do not matter).
  void normal4(double out[4]) {
    const std::uint64_t b = next();
    const double* t = normal_table();
    out[0] = t[b & 0xFFFF];
    out[1] = t[(b >> 16) & 0xFFFF];
    out[2] = t[(b >> 32) & 0xFFFF];
    out[3] = t[(b >> 48) & 0xFFFF];
  }

  /// Four uniforms in (0, 1) at 16-bit resolution from one 64-bit draw.
  void uniform4(double out[4]) {
    const std::uint64_t b = next();
    for (int i = 0; i < 4; ++i) {
      out[i] = (static_cast<double>((b >> (16 * i)) & 0xFFFF) + 0.5) / 65536.0;
    }
  }

  /// Standard normal by the Box-Muller transform (both values used).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = uniform();
    while (u1 <= 0.0) u1 = uniform();
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    constexpr double kTwoPi = 6.283185307179586;
    spare_ = r * std::sin(kTwoPi * u2);
    has_spare_ = true;
    return r * std::cos(kTwoPi * u2);
  }

 private:
  // The standard normal's quantiles at (k + 0.5) / 65536, k = 0..65535 (Acklam's rational
  // approximation refined by one Halley step: accurate to ~1e-15).
  static const double* normal_table();

  std::uint64_t state_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

inline const double* Rng::normal_table() {
  static const std::vector<double> table = [] {
    std::vector<double> t(65536);
    static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,
                               -2.759285104469687e+02, 1.383577518672690e+02,
                               -3.066479806614716e+01, 2.506628277459239e+00};
    static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02,
                               -1.556989798598866e+02, 6.680131188771972e+01,
                               -1.328068155288572e+01};
    static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01,
                               -2.400758277161838e+00, -2.549732539343734e+00,
                               4.374664141464968e+00,  2.938163982698783e+00};
    static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                               3.754408661907416e+00};
    for (std::size_t k = 0; k < t.size(); ++k) {
      const double p = (static_cast<double>(k) + 0.5) / 65536.0;
      double x;
      if (p < 0.02425) {
        const double q = std::sqrt(-2 * std::log(p));
        x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
            ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
      } else if (p > 1 - 0.02425) {
        const double q = std::sqrt(-2 * std::log(1 - p));
        x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
            ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
      } else {
        const double q = p - 0.5;
        const double r = q * q;
        x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
            (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
      }
      const double e = 0.5 * std::erfc(-x / std::sqrt(2.0)) - p;
      const double u = e * std::sqrt(2 * 3.14159265358979323846) * std::exp(x * x / 2);
      t[k] = x - u / (1 + x * u / 2);
    }
    return t;
  }();
  return table.data();
}

/// Stream ids: one per purpose (the values are part of the output's definition: never reorder).
enum class Stream : std::uint64_t {
  kScript = 1,
  kDepthNoise = 2,
  kRgbNoise = 3,
  kMaskEroded = 4,
  kMaskDilated = 5,
  kMaskMissing = 6,
  kMaskPersonMissed = 7,
  kDepthHoles = 8,
};

inline Rng stream(std::uint64_t seed, Stream s, std::uint64_t index = 0) {
  return Rng::stream(seed, static_cast<std::uint64_t>(s), index);
}

}  // namespace hbos::render
