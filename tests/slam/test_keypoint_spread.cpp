// spread_keypoints (frontend/keypoint_spread.hpp): each pyramid level keeps its share of the
// pool, and within a level every cell yields its best corner before any cell yields a second.

#include <catch2/catch.hpp>

#include "frontend/keypoint_spread.hpp"
#include "frontend/orb_extraction.hpp"
#include "test_frontend_support.hpp"

#include <hbos/error.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <map>
#include <random>
#include <vector>

using hbos::slam::spread_keypoints;

namespace {

cv::KeyPoint corner(float x, float y, float response, int octave = 0) {
  return {x, y, 31.f, -1.f, response, octave};
}

std::map<int, int> per_level(const std::vector<cv::KeyPoint>& kps) {
  std::map<int, int> n;
  for (const cv::KeyPoint& k : kps) ++n[k.octave];
  return n;
}

bool same(const cv::KeyPoint& a, const cv::KeyPoint& b) {
  return a.pt == b.pt && a.response == b.response && a.octave == b.octave;
}

}  // namespace

TEST_CASE("spreading keeps a pool no larger than the target as it is", "[frontend][spread]") {
  const std::vector<cv::KeyPoint> pool{corner(1, 1, 5), corner(2, 2, 9), corner(300, 2, 1)};
  const auto kept = spread_keypoints(pool, 3, 64.f);
  REQUIRE(kept.size() == 3);
  for (std::size_t i = 0; i < pool.size(); ++i) CHECK(same(kept[i], pool[i]));
  CHECK(spread_keypoints(pool, 0, 64.f).empty());
}

TEST_CASE("each cell gives its best corner before any cell gives its second",
          "[frontend][spread]") {
  // Cell (0, 0) holds five strong corners, cells (1, 0) and (0, 1) one weak corner each.
  std::vector<cv::KeyPoint> pool;
  for (float i = 0.f; i < 5.f; i += 1.f) pool.push_back(corner(5.f + i, 5.f, 100.f - i));
  pool.push_back(corner(70, 5, 2));
  pool.push_back(corner(5, 70, 1));
  const auto kept = spread_keypoints(pool, 3, 64.f);
  REQUIRE(kept.size() == 3);
  CHECK(same(kept[0], pool[0]));  // the strongest of the crowded cell
  CHECK(same(kept[1], pool[5]));  // and the lone corner of each other cell
  CHECK(same(kept[2], pool[6]));
  // With room for four, the crowded cell's second corner comes next, not its weaker ones.
  const auto four = spread_keypoints(pool, 4, 64.f);
  REQUIRE(four.size() == 4);
  CHECK(same(four[1], pool[1]));
  // Within a round the strongest cells go first: room for two keeps the two strongest cells.
  const auto two = spread_keypoints(pool, 2, 64.f);
  REQUIRE(two.size() == 2);
  CHECK(same(two[0], pool[0]));
  CHECK(same(two[1], pool[5]));
}

TEST_CASE("each level keeps its share of the pool, by largest remainder", "[frontend][spread]") {
  std::vector<cv::KeyPoint> pool;
  for (float i = 0.f; i < 7.f; i += 1.f) pool.push_back(corner(10.f * i, 0, 1.f + i, 0));
  for (float i = 0.f; i < 2.f; i += 1.f) pool.push_back(corner(10.f * i, 50, 1.f + i, 1));
  pool.push_back(corner(0, 100, 1, 2));
  // Shares of 4: 2.8, 0.8, 0.4 -> floors 2, 0, 0; the two largest remainders (level 0 first,
  // then level 1) get the other two.
  auto n = per_level(spread_keypoints(pool, 4, 64.f));
  CHECK(n[0] == 3);
  CHECK(n[1] == 1);
  CHECK(n.count(2) == 0);
}

TEST_CASE("spreading a random pool: the target met, the levels' quotas met, the pool's order kept",
          "[frontend][spread]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> x(0.f, 640.f), y(0.f, 480.f), r(0.f, 1.f);
  std::uniform_int_distribution<int> level(0, 7), size(1, 400);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<cv::KeyPoint> pool(static_cast<std::size_t>(size(rng)));
    for (cv::KeyPoint& k : pool) k = corner(x(rng), y(rng), r(rng), level(rng));
    const int target = std::uniform_int_distribution<int>(1, 450)(rng);
    const float cell = std::uniform_real_distribution<float>(4.f, 200.f)(rng);
    const auto kept = spread_keypoints(pool, target, cell);
    REQUIRE(kept.size() == std::min<std::size_t>(pool.size(), static_cast<std::size_t>(target)));
    // A subsequence of the pool.
    std::size_t at = 0;
    for (const cv::KeyPoint& k : kept) {
      while (at < pool.size() && !same(pool[at], k)) ++at;
      REQUIRE(at < pool.size());
      ++at;
    }
    if (static_cast<std::size_t>(target) >= pool.size()) continue;
    // Every level within one keypoint of its exact share.
    const auto in_pool = per_level(pool);
    auto in_kept = per_level(kept);
    for (const auto& [lvl, m] : in_pool) {
      const double share = static_cast<double>(target) * m / static_cast<double>(pool.size());
      CHECK(in_kept[lvl] >= static_cast<int>(share));
      CHECK(in_kept[lvl] <= static_cast<int>(share) + 1);
    }
  }
}

TEST_CASE(
    "the extractor's spread keeps the feature count and thins the most crowded cell on a "
    "real frame",
    "[frontend][spread]") {
  // The first bundled fr1/xyz frame: a desk whose textured clutter takes cv::ORB's strongest
  // corners in a few regions.
  hbos::slam::Frame frame;
  frame.bgr = cv::imread(hbos_test::slam_data("fr1_xyz_37/rgb/1305031102.175304.jpg").string(),
                         cv::IMREAD_COLOR);
  REQUIRE(!frame.bgr.empty());
  frame.depth_m = cv::Mat::zeros(frame.bgr.size(), CV_32F);
  const auto camera = hbos::slam::camera_preset("tum1");
  const auto crowd = [](const hbos::slam::Features& f) {
    std::map<std::pair<int, int>, int> n;
    int most = 0;
    for (const cv::KeyPoint& k : f.keypoints)
      most =
          std::max(most, ++n[{static_cast<int>(k.pt.x / 128.f), static_cast<int>(k.pt.y / 128.f)}]);
    return most;
  };
  hbos::slam::ExtractionConfig off;
  hbos::slam::ExtractionConfig on;
  on.spread_cell_px = 128.f;
  hbos::slam::OrbExtractor plain(off, camera);
  hbos::slam::OrbExtractor spread(on, camera);
  const auto a = plain.extract(frame);
  const auto b = spread.extract(frame);
  CHECK(a.size() == static_cast<std::size_t>(off.features));
  CHECK(b.size() == static_cast<std::size_t>(on.features));  // compute() dropped none
  CHECK(b.descriptors.rows == static_cast<int>(b.size()));
  CHECK(crowd(b) < crowd(a));
  hbos::slam::ExtractionConfig too_large = on;
  too_large.features = 50000;
  CHECK_THROWS_AS(hbos::slam::OrbExtractor(too_large, camera), hbos::InvalidArgument);
}
