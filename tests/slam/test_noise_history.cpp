// The map tracker's residual history as the screen's persistence evidence
// (frontend/map/noise_history.hpp): each point's share q / (q + ratio * median q).

#include <catch2/catch.hpp>

#include "frontend/map/noise_history.hpp"

#include <hbos/error.hpp>

#include <cmath>
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

}  // namespace

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

TEST_CASE("noise history: shares are in [0, 1], monotone in q, and free of the frame's scale",
          "[map][noise_history]") {
  std::mt19937 rng(11);
  std::gamma_distribution<double> spread(1.5, 1.0);
  slam::NoiseHistoryConfig c;
  for (int trial = 0; trial < 20; ++trial) {
    const std::size_t n = 10 + static_cast<std::size_t>(trial) * 13;
    std::vector<double> q(n);
    for (double& v : q) v = spread(rng);
    const double k = 0.3 * (trial + 1);
    std::vector<slam::PointNoise> base, scaled;
    for (const double v : q) {
      base.push_back(noise_of(v, 2));
      scaled.push_back(noise_of(k * v, 2));
    }
    const std::vector<double> a = slam::noise_shares(base, c);
    const std::vector<double> b = slam::noise_shares(scaled, c);
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

TEST_CASE("noise history: settings out of range throw, naming the setting and value",
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
