// The map tracker's per-point noise (frontend/map/point_noise.hpp): the running mean each map
// point keeps of its squared whitened residual, and how the final refinement widens the sigma of
// the points whose mean stands out from the frame's; and the same record as the screen's
// persistence evidence (frontend/map/noise_history.hpp), each point's share
// q / (q + ratio * median q).

#include <catch2/catch.hpp>

#include "frontend/map/noise_history.hpp"
#include "frontend/map/point_noise.hpp"

#include <hbos/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace slam = hbos::slam;

namespace {

slam::PointNoise noise_of(double mean_square, int frames) {
  slam::PointNoise n;
  for (int k = 0; k < frames; ++k) n.record(mean_square, 0.8);  // a constant keeps its mean
  return n;
}

/// A frame of n points with random mean squares q (a gamma draw), recorded twice: as drawn and
/// k times larger (the same frame, noisier). The properties below must not see the difference.
struct ScaledFrames {
  std::vector<double> q;
  std::vector<slam::PointNoise> base, scaled;
};

ScaledFrames random_scaled_frames(std::mt19937& rng, std::size_t n, double k) {
  std::gamma_distribution<double> spread(1.5, 1.0);
  ScaledFrames f;
  f.q.resize(n);
  for (double& v : f.q) v = spread(rng);
  for (const double v : f.q) {
    f.base.push_back(noise_of(v, 2));
    f.scaled.push_back(noise_of(k * v, 2));
  }
  return f;
}

}  // namespace

TEST_CASE("point noise: the first record is the mean, then the past fades by `memory`",
          "[map][point_noise]") {
  slam::PointNoise n;
  CHECK(n.frames() == 0);
  CHECK(n.mean_square() == 0.0);
  n.record(4.0, 0.8);
  CHECK(n.mean_square() == 4.0);
  n.record(9.0, 0.8);
  CHECK(n.mean_square() == Approx(0.8 * 4.0 + 0.2 * 9.0));
  CHECK(n.frames() == 2);
  // A residual that is not finite (a point behind a wrong pose) tells nothing: not recorded.
  n.record(std::numeric_limits<double>::infinity(), 0.8);
  n.record(std::numeric_limits<double>::quiet_NaN(), 0.8);
  CHECK(n.frames() == 2);
  CHECK(n.mean_square() == Approx(0.8 * 4.0 + 0.2 * 9.0));
}

TEST_CASE("point noise: points beyond tolerance x the median get the weight of their noise",
          "[map][point_noise]") {
  slam::PointNoiseConfig c;  // tolerance 2, min_frames 2
  std::vector<slam::PointNoise> noise;
  for (int i = 0; i < 20; ++i) noise.push_back(noise_of(1.0 + 0.01 * i, 3));  // median 1.10
  noise.push_back(noise_of(8.8, 3));   // 4 x the reference 2 x 1.10: weight 1/4
  noise.push_back(noise_of(2.2, 3));   // exactly at the reference: kept as it is
  noise.push_back(noise_of(50.0, 1));  // one frame only: its noise does not count yet
  std::vector<std::uint8_t> use(noise.size(), 1);
  std::vector<double> sigma(noise.size(), 1.5);
  slam::widen_by_point_noise(noise, use, c, sigma);
  const double median = 1.11;  // 22 known values: the upper middle one (nth_element at 11)
  for (int i = 0; i < 20; ++i) CHECK(sigma[static_cast<std::size_t>(i)] == 1.5);
  CHECK(sigma[20] == Approx(1.5 * std::sqrt(8.8 / (2.0 * median))));
  CHECK(sigma[21] == 1.5);
  CHECK(sigma[22] == 1.5);
  // The weight 1/sigma^2 falls as the reference over the point's own mean square.
  CHECK(1.5 * 1.5 / (sigma[20] * sigma[20]) == Approx(2.0 * median / 8.8));
}

TEST_CASE("point noise: the widening is the same whatever the frame's noise level",
          "[map][point_noise]") {
  // A noisier frame (every mean square k times larger) must not down-weight every point: the
  // reference is the frame's own median.
  std::mt19937 rng(7);
  slam::PointNoiseConfig c;
  for (int trial = 0; trial < 20; ++trial) {
    const std::size_t n = 10 + static_cast<std::size_t>(trial) * 17;
    const ScaledFrames f = random_scaled_frames(rng, n, 0.25 * (trial + 1));
    std::vector<std::uint8_t> use(n);
    for (std::size_t i = 0; i < n; ++i) use[i] = i % 5 != 0 ? 1 : 0;
    std::vector<double> sigma_base(n, 1.0), sigma_scaled(n, 1.0);
    slam::widen_by_point_noise(f.base, use, c, sigma_base);
    slam::widen_by_point_noise(f.scaled, use, c, sigma_scaled);
    int widened = 0;
    for (std::size_t i = 0; i < n; ++i) {
      CHECK(sigma_scaled[i] == Approx(sigma_base[i]).epsilon(1e-12));
      CHECK(sigma_base[i] >= 1.0);  // never narrower than the octave's sigma
      widened += sigma_base[i] > 1.0 ? 1 : 0;
    }
    // With 4 in 5 used, fewer than 10 known points leave every sigma as it was.
    const std::size_t used = static_cast<std::size_t>(std::count(use.begin(), use.end(), 1));
    if (used < 10) CHECK(widened == 0);
  }
}

TEST_CASE("point noise: unused points set no reference, but are widened by it",
          "[map][point_noise]") {
  slam::PointNoiseConfig c;
  std::vector<slam::PointNoise> noise;
  for (int i = 0; i < 10; ++i) noise.push_back(noise_of(1.0, 2));
  for (int i = 0; i < 30; ++i) noise.push_back(noise_of(100.0, 2));  // rejected: not used
  std::vector<std::uint8_t> use(noise.size(), 0);
  for (int i = 0; i < 10; ++i) use[static_cast<std::size_t>(i)] = 1;
  std::vector<double> sigma(noise.size(), 1.0);
  slam::widen_by_point_noise(noise, use, c, sigma);
  CHECK(sigma[0] == 1.0);
  CHECK(sigma[39] == Approx(std::sqrt(100.0 / 2.0)));
  // Nine used points with a history are too few to set the reference.
  use[9] = 0;
  std::vector<double> unchanged(noise.size(), 1.0);
  slam::widen_by_point_noise(noise, use, c, unchanged);
  CHECK(unchanged == std::vector<double>(noise.size(), 1.0));
}

TEST_CASE("point noise: mismatched inputs and settings out of range throw", "[map][point_noise]") {
  std::vector<slam::PointNoise> noise(3);
  std::vector<std::uint8_t> use(3, 1);
  std::vector<double> sigma(2, 1.0);
  slam::PointNoiseConfig c;
  CHECK_THROWS_AS(slam::widen_by_point_noise(noise, use, c, sigma), hbos::InvalidArgument);
  sigma.resize(3, 1.0);
  c.tolerance = 0.5;
  CHECK_THROWS_WITH(slam::widen_by_point_noise(noise, use, c, sigma),
                    Catch::Contains("tolerance") && Catch::Contains("0.5"));
  c = {};
  c.memory = 1.0;
  CHECK_THROWS_WITH(slam::widen_by_point_noise(noise, use, c, sigma), Catch::Contains("memory"));
  c = {};
  c.min_frames = 0;
  CHECK_THROWS_WITH(slam::widen_by_point_noise(noise, use, c, sigma),
                    Catch::Contains("min_frames"));
}

TEST_CASE("noise history: a point at ratio x the frame's median gets one half",
          "[map][noise_history]") {
  slam::NoiseHistoryConfig c;  // ratio 2, min_frames 2
  std::vector<slam::PointNoise> noise;
  for (int i = 0; i < 20; ++i) noise.push_back(noise_of(1.0 + 0.01 * i, 3));
  noise.push_back(noise_of(4.4, 3));    // about 4 x the median
  noise.push_back(noise_of(44.0, 3));   // 40 x: near 1
  noise.push_back(noise_of(50.0, 1));   // one frame only: no record yet
  noise.push_back(slam::PointNoise{});  // never screened
  const std::vector<double> s = slam::noise_shares(noise, c);
  REQUIRE(s.size() == noise.size());
  const double median = 1.11;  // 22 known values: the upper middle one (nth_element at 11)
  CHECK(s[0] == Approx(1.0 / (1.0 + c.ratio * median)));
  CHECK(s[20] == Approx(4.4 / (4.4 + c.ratio * median)));
  CHECK(s[21] == Approx(44.0 / (44.0 + c.ratio * median)));
  CHECK(s[22] == 0.0);
  CHECK(s[23] == 0.0);
  // At exactly ratio x the median the share is the history feature's floor.
  noise[20] = noise_of(c.ratio * median, 3);
  CHECK(slam::noise_shares(noise, c)[20] == Approx(0.5));
}

TEST_CASE("noise history: shares lie between 0 and 1 and grow with q whatever the frame's scale",
          "[map][noise_history]") {
  std::mt19937 rng(11);
  slam::NoiseHistoryConfig c;
  for (int trial = 0; trial < 20; ++trial) {
    const std::size_t n = 10 + static_cast<std::size_t>(trial) * 13;
    const ScaledFrames f = random_scaled_frames(rng, n, 0.3 * (trial + 1));
    const std::vector<double>& q = f.q;
    const std::vector<double> a = slam::noise_shares(f.base, c);
    const std::vector<double> b = slam::noise_shares(f.scaled, c);
    for (std::size_t i = 0; i < n; ++i) {
      CHECK(a[i] >= 0.0);
      CHECK(a[i] <= 1.0);
      CHECK(b[i] == Approx(a[i]).epsilon(1e-12));
      for (std::size_t j = 0; j < n; ++j)
        if (q[i] < q[j]) CHECK(a[i] <= a[j]);
    }
  }
}

TEST_CASE("noise history: too few records, a zero median or a mean at the top of the range",
          "[map][noise_history]") {
  slam::NoiseHistoryConfig c;
  std::vector<slam::PointNoise> noise;
  for (int i = 0; i < 9; ++i) noise.push_back(noise_of(1.0, 2));
  noise.push_back(noise_of(100.0, 1));
  // Nine points with enough records cannot say what the frame's typical residual is.
  CHECK(slam::noise_shares(noise, c) == std::vector<double>(noise.size(), 0.0));
  std::vector<slam::PointNoise> zeros(12, noise_of(0.0, 3));
  CHECK(slam::noise_shares(zeros, c) == std::vector<double>(zeros.size(), 0.0));
  // A mean at the top of the double range (0.8 max + 0.2 max may round past it to infinity)
  // says "far off": a share of at most 1, never NaN.
  std::vector<slam::PointNoise> big(12, noise_of(1.0, 3));
  big[0] = noise_of(std::numeric_limits<double>::max(), 3);
  const std::vector<double> s = slam::noise_shares(big, c);
  CHECK(std::isfinite(s[0]));
  CHECK(s[0] <= 1.0);
  CHECK(s[0] > 0.99);
}

TEST_CASE("noise history: settings out of range throw naming the setting and value",
          "[map][noise_history]") {
  const std::vector<slam::PointNoise> noise(12, noise_of(1.0, 2));
  slam::NoiseHistoryConfig c;
  c.ratio = 0.5;
  CHECK_THROWS_WITH(slam::noise_shares(noise, c),
                    Catch::Contains("ratio") && Catch::Contains("0.5"));
  c = {};
  c.ratio = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(slam::noise_shares(noise, c), hbos::InvalidArgument);
  c = {};
  c.memory = 1.0;
  CHECK_THROWS_WITH(slam::noise_shares(noise, c), Catch::Contains("memory"));
  c = {};
  c.min_frames = 0;
  CHECK_THROWS_WITH(slam::noise_shares(noise, c), Catch::Contains("min_frames"));
}
