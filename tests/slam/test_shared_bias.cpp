// The offset static neighbours share (frontend/shared_bias.hpp), on residual fields whose truth
// is known: independent noise (no shared offset), cells that each share a drawn offset of a
// known size, and the same with a few cells that hold something moving.

#include <catch2/catch.hpp>

#include "frontend/shared_bias.hpp"

#include <hbos/error.hpp>

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <utility>
#include <vector>

using hbos::slam::shared_bias_scales;

namespace {

struct Field {
  std::vector<Eigen::Vector2d> pixel, residual;
};

// 2000 matches over a 640 x 480 image, residuals of noise s per axis [sigma units] plus, per
// 40 px cell, an offset of `bias` s per axis (N(0, (bias s)^2)); `moving` cells get 5 s more.
Field field(unsigned seed, double s, double bias, int moving = 0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 640.0), v(0.0, 480.0);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::map<std::pair<int, int>, Eigen::Vector2d> offset;
  Field f;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d p(u(rng), v(rng));
    const std::pair<int, int> cell(static_cast<int>(p.x() / 40.0), static_cast<int>(p.y() / 40.0));
    auto it = offset.find(cell);
    if (it == offset.end()) {
      Eigen::Vector2d o(unit(rng), unit(rng));
      o *= bias * s;
      if (static_cast<int>(offset.size()) < moving) o += Eigen::Vector2d(5.0 * s, 0.0);
      it = offset.emplace(cell, o).first;
    }
    f.pixel.push_back(p);
    f.residual.push_back(it->second + s * Eigen::Vector2d(unit(rng), unit(rng)));
  }
  return f;
}

}  // namespace

TEST_CASE("shared bias: independent noise shares nothing, shared offsets are measured",
          "[frontend][shared_bias]") {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    CAPTURE(seed);
    const Field independent = field(seed, 0.6, 0.0);
    CHECK(shared_bias_scales(independent.pixel, independent.residual, 0.6, 40.0) < 0.15);
    for (const double bias : {0.3, 0.6}) {
      CAPTURE(bias);
      const Field shared = field(seed, 0.6, bias);
      const double b = shared_bias_scales(shared.pixel, shared.residual, 0.6, 40.0);
      CHECK(b > 0.6 * bias);
      CHECK(b < 1.4 * bias);
    }
  }
}

TEST_CASE("shared bias: a few cells that hold something moving barely move it",
          "[frontend][shared_bias]") {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    CAPTURE(seed);
    const Field quiet = field(seed, 0.6, 0.3);
    const Field busy = field(seed, 0.6, 0.3, 6);  // 6 of about 190 cells, 5 noise scales off
    const double b_quiet = shared_bias_scales(quiet.pixel, quiet.residual, 0.6, 40.0);
    const double b_busy = shared_bias_scales(busy.pixel, busy.residual, 0.6, 40.0);
    CHECK(b_busy >= b_quiet);
    CHECK(b_busy - b_quiet < 0.1);
  }
}

TEST_CASE("shared bias: properties and edge cases", "[frontend][shared_bias]") {
  const Field f = field(7, 0.8, 0.4);
  const double b = shared_bias_scales(f.pixel, f.residual, 0.8, 40.0);
  REQUIRE(b > 0.0);

  SECTION("in noise scales: residuals and noise scaled together give the same value") {
    Field g = f;
    for (Eigen::Vector2d& r : g.residual) r *= 4.0;  // a power of two: the same bits
    CHECK(shared_bias_scales(g.pixel, g.residual, 3.2, 40.0) == b);
  }
  SECTION("the order of the matches does not matter") {
    Field g = f;
    std::mt19937 rng(3);
    for (std::size_t i = g.pixel.size() - 1; i > 0; --i) {
      const std::size_t j = std::uniform_int_distribution<std::size_t>(0, i)(rng);
      std::swap(g.pixel[i], g.pixel[j]);
      std::swap(g.residual[i], g.residual[j]);
    }
    CHECK(std::abs(shared_bias_scales(g.pixel, g.residual, 0.8, 40.0) - b) < 1e-9);
  }
  SECTION("too few usable cells: no evidence of a shared offset") {
    // Cells of 500 px: 2 cells over the image, fewer than the 4 needed.
    CHECK(shared_bias_scales(f.pixel, f.residual, 0.8, 500.0) == 0.0);
    CHECK(shared_bias_scales({}, {}, 0.8, 40.0) == 0.0);
    // 40 px cells that each hold fewer than 8 matches.
    const std::vector<Eigen::Vector2d> sparse_pixel(f.pixel.begin(), f.pixel.begin() + 100);
    const std::vector<Eigen::Vector2d> sparse_residual(f.residual.begin(),
                                                       f.residual.begin() + 100);
    CHECK(shared_bias_scales(sparse_pixel, sparse_residual, 0.8, 40.0) == 0.0);
  }
  SECTION("non-finite matches are skipped") {
    Field g = f;
    g.pixel.emplace_back(std::nan(""), 10.0);
    g.residual.emplace_back(1.0, 1.0);
    g.pixel.emplace_back(10.0, 10.0);
    g.residual.emplace_back(std::numeric_limits<double>::infinity(), 0.0);
    CHECK(shared_bias_scales(g.pixel, g.residual, 0.8, 40.0) == b);
  }
  SECTION("bad inputs are refused by name") {
    CHECK_THROWS_WITH(shared_bias_scales(f.pixel, {}, 0.8, 40.0), Catch::Contains("2000 pixels"));
    for (const double bad : {0.0, -1.0, std::numeric_limits<double>::infinity(), std::nan("")}) {
      CHECK_THROWS_AS(shared_bias_scales(f.pixel, f.residual, bad, 40.0), hbos::InvalidArgument);
      CHECK_THROWS_WITH(shared_bias_scales(f.pixel, f.residual, 0.8, bad),
                        Catch::Contains("cell size"));
    }
  }
}
