// The variant grid (hbos-slam --variant-grid): the variants of the rule, the parallax residual
// of the person, and a short grid that resumes from its cache.

#include <catch2/catch.hpp>

#include "frontend/grid/grid_report.hpp"
#include "frontend/grid/grid_run.hpp"
#include "frontend/grid/parallax.hpp"
#include "frontend/grid/variants.hpp"
#include "frontend/standing.hpp"
#include "test_frontend_support.hpp"

#include <cmath>
#include <string>
#include <vector>

using hbos_test::ScratchDir;
using hbos_test::slam_data;

TEST_CASE("the grid's variants follow the rule and stay in view", "[frontend][grid]") {
  const auto variants = hbos::slam::semireal_variants(640, 210);
  REQUIRE(variants.size() == 8);
  CHECK(variants.front().depth_m == 0.7);  // the demo's own path first
  CHECK(variants.front().speed_px_per_frame == 5.5);
  CHECK(variants.front().start_x_px == 40.0);
  for (const auto& v : variants) {
    const double end = v.start_x_px + 36 * v.speed_px_per_frame;
    CHECK(std::min(v.start_x_px, end) >= 0.0);
    CHECK(std::max(v.start_x_px, end) + 210 <= 640.0);
  }
}

TEST_CASE("the default's standing: best at or below, tied within the spread, behind past it",
          "[frontend][grid]") {
  using hbos::slam::Standing;
  using hbos::slam::standing;
  using hbos::slam::to_string;
  CHECK(standing(1.0, 1.0, 0.0) == Standing::best);  // equal means: the default is not behind
  CHECK(standing(0.9, 1.0, 0.0) == Standing::best);
  CHECK(standing(1.25, 1.0, 0.25) == Standing::tied);  // a gap of exactly the spread ties
  CHECK(standing(1.2500001, 1.0, 0.25) == Standing::behind);
  CHECK(standing(1.0000001, 1.0, 0.0) == Standing::behind);  // no spread: any gap is behind
  // Monotone in the default's mean: walking it upwards never goes back to a better standing.
  for (const double spread : {0.0, 0.05, 0.4}) {
    int last = 0;
    for (double mean = 0.5; mean < 2.0; mean += 0.01) {
      const int now = static_cast<int>(standing(mean, 1.0, spread));
      CHECK(now >= last);
      last = now;
    }
    CHECK(last == static_cast<int>(Standing::behind));
  }
  CHECK(std::string(to_string(Standing::tied)) == "tied");
  CHECK(std::string(to_string(Standing::behind)) == "behind");
  CHECK(std::string(to_string(Standing::best)) == "best");
}

TEST_CASE("the parallax residual: zero where the person moves with a static point's flow",
          "[frontend][grid]") {
  hbos::slam::CameraModel camera;
  camera.fx = camera.fy = 500.0;
  camera.cx = 320.0;
  camera.cy = 240.0;
  const std::vector<double> stamps = {0.0, 0.1, 0.2};
  hbos::slam::ScenarioConfig scenario;
  scenario.depth_m = 1.0;
  scenario.start_x_px = 200.0;
  std::vector<Eigen::Isometry3d> poses(3, Eigen::Isometry3d::Identity());
  // A flat cut-out 100 x 200 px, all person, all at the median depth.
  hbos::slam::PersonCutout cutout;
  cutout.bgr = cv::Mat(200, 100, CV_8UC3, cv::Scalar(0, 0, 0));
  cutout.mask = cv::Mat(200, 100, CV_8UC1, cv::Scalar(255));
  cutout.relative_depth = cv::Mat(200, 100, CV_32FC1, cv::Scalar(1.0));
  const cv::Size image(640, 480);
  SECTION("a still camera: the residual is the person's own motion") {
    scenario.speed_px_per_frame = 4.0;
    const auto gt = hbos::slam::make_trajectory("gt", stamps, poses);
    const auto r = hbos::slam::person_parallax_px(gt, stamps, camera, scenario, cutout, image);
    CHECK(std::isnan(r[0]));
    CHECK(r[1] == Approx(4.0));
    CHECK(r[2] == Approx(4.0));
  }
  SECTION("the camera moving right 1 cm per frame: a point at 1 m flows 5 px left") {
    for (int i = 0; i < 3; ++i) poses[static_cast<std::size_t>(i)].translation().x() = 0.01 * i;
    const auto gt = hbos::slam::make_trajectory("gt", stamps, poses);
    scenario.speed_px_per_frame = -5.0;
    auto r = hbos::slam::person_parallax_px(gt, stamps, camera, scenario, cutout, image);
    CHECK(r[1] == Approx(0.0).margin(1e-9));
    CHECK(r[1] < hbos::slam::kHiddenParallaxPx);
    scenario.speed_px_per_frame = 5.0;
    r = hbos::slam::person_parallax_px(gt, stamps, camera, scenario, cutout, image);
    CHECK(r[2] == Approx(10.0));
  }
}

TEST_CASE("a short grid runs every variant and mask, and resumes from its cache",
          "[frontend][grid]") {
  hbos::slam::Config config;
  config.dataset.path = slam_data("fr1_xyz_37").string();
  config.dataset.max_frames = 4;  // the per-frame RPE needs 4 poses
  config.scenario.person_dir = slam_data("person").string();
  config.mask.detector_dir = slam_data("models/yolo-fastest-1.1_body").string();
  const auto sequence = hbos::slam::load_tum_sequence(config.dataset.path);
  const auto camera = hbos::slam::camera_preset("tum1");
  const ScratchDir dir("grid");
  // Two screens keep the test short (the full grid is the documented --variant-grid run).
  const std::vector<std::string> screens = {"default", "none"};
  const auto first = hbos::slam::run_variant_grid(config, sequence, camera, dir.file("runs"),
                                                  nullptr, nullptr, screens);
  REQUIRE(first.complete);
  REQUIRE(first.runs.size() == 8 * 3 * 2);
  CHECK(first.reused == 0);
  for (const auto& r : first.runs) {
    CHECK(r.frames == 4);
    CHECK(r.ate_rmse_m < 0.05);
    CHECK(r.frame_person_matches.size() == 4);
    if (r.screen == "none") CHECK(r.person_survivors == r.person_matches);
  }
  const auto again = hbos::slam::run_variant_grid(config, sequence, camera, dir.file("runs"),
                                                  nullptr, nullptr, screens);
  CHECK(again.reused == 48);
  for (std::size_t i = 0; i < again.runs.size(); ++i) {
    CHECK(again.runs[i].ate_rmse_m == first.runs[i].ate_rmse_m);
  }
  const auto verdicts = hbos::slam::grid_verdicts(first, hbos::slam::grid_cells(first));
  CHECK(verdicts.size() == 3 * 2);  // per mask: ATE and RPE
  const auto json = hbos::slam::grid_json(first, "test");
  CHECK(json.at("runs").size() == 48);
  CHECK(json.at("cells").size() == 6);
  CHECK(json.at("variants").size() == 8);
}
