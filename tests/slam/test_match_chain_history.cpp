// The screen's memory along a chain of matches (frontend/outlier_share.hpp) and when the frame
// tracker passes it (frame_history_wanted).

#include <catch2/catch.hpp>

#include "frontend/config.hpp"
#include "frontend/outlier_share.hpp"
#include "frontend/tracker.hpp"

#include <cmath>
#include <random>
#include <vector>

TEST_CASE("outlier share: the forgetting-weighted share of rejections, by its definition",
          "[frontend][history]") {
  CHECK(hbos::slam::OutlierShare{}.share() == 0.0);  // never screened
  std::mt19937 rng(7);
  std::bernoulli_distribution coin(0.3);
  std::uniform_real_distribution<double> lambda_of(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double lambda = trial == 0 ? 0.0 : trial == 1 ? 1.0 : lambda_of(rng);
    const int length = 1 + trial % 25;
    std::vector<bool> rejected(static_cast<std::size_t>(length));
    hbos::slam::OutlierShare share;
    for (int k = 0; k < length; ++k) {
      rejected[static_cast<std::size_t>(k)] = coin(rng);
      share.record(rejected[static_cast<std::size_t>(k)], lambda);
    }
    // share = sum_k lambda^k r_k / sum_k lambda^k, k screenings ago (0^0 = 1).
    double num = 0.0, den = 0.0;
    for (int k = 0; k < length; ++k) {
      const double w = std::pow(lambda, length - 1 - k);
      num += rejected[static_cast<std::size_t>(k)] ? w : 0.0;
      den += w;
    }
    INFO("trial " << trial << ", lambda " << lambda);
    CHECK(share.share() == Approx(num / den).margin(1e-12));
    CHECK(share.share() >= 0.0);
    CHECK(share.share() <= 1.0);
  }
}

TEST_CASE("match chain history: passed only when asked for and to a screen that reads it",
          "[frontend][history]") {
  hbos::slam::Config c;
  c.screen.select("default");
  c.screen.track_history = false;
  CHECK_FALSE(hbos::slam::frame_history_wanted(c));
  c.screen.track_history = true;
  CHECK(hbos::slam::frame_history_wanted(c));
  for (const char* other : {"chi2", "fixed", "quantile", "mad", "magnitude", "paper", "none"}) {
    c.screen.select(other);
    INFO(other);
    CHECK_FALSE(hbos::slam::frame_history_wanted(c));
  }
}
