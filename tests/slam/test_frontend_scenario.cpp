// The labelled dynamic scenario: the person cut-out is composited where and how it should be,
// and the masks derived from the label (exact, degraded) have the promised properties.

#include <catch2/catch.hpp>

#include "frontend/frame_source.hpp"
#include "frontend/person_mask.hpp"
#include "frontend/person_scenario.hpp"
#include "test_frontend_support.hpp"

#include <hbos/error.hpp>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

using Catch::Matchers::Contains;
using hbos_test::slam_data;

namespace {

hbos::slam::ScenarioConfig person_scenario() {
  hbos::slam::ScenarioConfig s;
  s.add_person = true;
  s.person_dir = slam_data("person").string();
  return s;
}

float median_of(std::vector<float> values) {
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2),
                   values.end());
  return values[values.size() / 2];
}

}  // namespace

TEST_CASE("compositing writes the person and labels exactly its pixels", "[frontend][scenario]") {
  const hbos::slam::ScenarioConfig config = person_scenario();
  const hbos::slam::PersonCutout cutout = hbos::slam::load_person_cutout(config.person_dir);
  const int person_pixels = cv::countNonZero(cutout.mask);
  REQUIRE(person_pixels > 10000);
  const hbos::slam::PersonCompositor compositor(cutout, config);

  for (const int index : {0, 10, 36}) {
    cv::Mat bgr(480, 640, CV_8UC3, cv::Scalar(10, 20, 30));
    cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(2.5f));
    const cv::Mat label = compositor.composite(index, bgr, depth);
    // The whole cut-out is inside the image on these frames: every person pixel is labelled.
    REQUIRE(cv::countNonZero(label) == person_pixels);
    const cv::Rect box = cv::boundingRect(label);
    const cv::Rect cut = cv::boundingRect(cutout.mask);
    const int expected_x =
        static_cast<int>(std::lround(config.start_x_px + config.speed_px_per_frame * index));
    CHECK(box.x == expected_x + cut.x);
    CHECK(box.y + box.height == 480);  // standing on the image's bottom edge
    std::vector<float> person_depth;
    int touched_outside = 0, wrong_colour = 0;
    for (int y = 0; y < 480; ++y) {
      for (int x = 0; x < 640; ++x) {
        if (label.at<std::uint8_t>(y, x) == 0) {
          // Untouched outside the label.
          touched_outside +=
              (bgr.at<cv::Vec3b>(y, x) != cv::Vec3b(10, 20, 30) || depth.at<float>(y, x) != 2.5f)
                  ? 1
                  : 0;
          continue;
        }
        const cv::Point in_cutout(x - expected_x, y - (480 - cutout.bgr.rows));
        wrong_colour += bgr.at<cv::Vec3b>(y, x) != cutout.bgr.at<cv::Vec3b>(in_cutout) ? 1 : 0;
        if (depth.at<float>(y, x) > 0.f) person_depth.push_back(depth.at<float>(y, x));
      }
    }
    CHECK(touched_outside == 0);
    CHECK(wrong_colour == 0);
    // The person stands at the configured depth (its own shape kept around the median).
    CHECK(median_of(person_depth) == Approx(config.depth_m).epsilon(0.01));
  }
}

TEST_CASE("a person partly outside the image is clipped", "[frontend][scenario]") {
  hbos::slam::ScenarioConfig config = person_scenario();
  config.start_x_px = 560.0;  // only the left ~80 px of the cut-out are in view
  const hbos::slam::PersonCompositor compositor(hbos::slam::load_person_cutout(config.person_dir),
                                                config);
  cv::Mat bgr(480, 640, CV_8UC3, cv::Scalar(0, 0, 0));
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(1.f));
  const cv::Mat label = compositor.composite(0, bgr, depth);
  const int visible = cv::countNonZero(label);
  CHECK(visible > 0);
  CHECK(visible < cv::countNonZero(hbos::slam::load_person_cutout(config.person_dir).mask));
  CHECK(cv::boundingRect(label).br().x == 640);
}

TEST_CASE("the person cut-out: missing files are named", "[frontend][scenario]") {
  CHECK_THROWS_WITH(hbos::slam::load_person_cutout("/nonexistent/person"),
                    Contains("/nonexistent/person/rgb.png"));
}

TEST_CASE("the degraded mask leaks edges and legs and misses every 5th frame", "[frontend][mask]") {
  const hbos::slam::PersonCutout cutout =
      hbos::slam::load_person_cutout(slam_data("person").string());
  cv::Mat exact(480, 640, CV_8UC1, cv::Scalar(0));
  cutout.mask.copyTo(
      exact(cv::Rect(100, 480 - cutout.mask.rows, cutout.mask.cols, cutout.mask.rows)));
  const hbos::slam::MaskConfig config;
  const cv::Rect person = cv::boundingRect(exact);
  for (int index = 0; index < 10; ++index) {
    const cv::Mat degraded = hbos::slam::degrade_mask(exact, index, config);
    if (index % 5 == 4) {
      CHECK(cv::countNonZero(degraded) == 0);
      continue;
    }
    // A strict subset of the exact mask...
    CHECK(cv::countNonZero(degraded & ~exact) == 0);
    CHECK(cv::countNonZero(degraded) < cv::countNonZero(exact));
    // ... with the lower 40 % of the person unmasked ...
    const int cut = person.y + static_cast<int>(std::lround(0.6 * person.height));
    CHECK(cv::countNonZero(degraded.rowRange(cut, 480)) == 0);
    // ... and the silhouette's edge eroded (the exact mask's boundary pixels are all unmasked).
    cv::Mat boundary;
    cv::Mat eroded_by_one;
    cv::erode(exact, eroded_by_one, cv::Mat());
    boundary = exact & ~eroded_by_one;
    CHECK(cv::countNonZero(degraded & boundary) == 0);
    CHECK(cv::countNonZero(degraded.rowRange(0, cut)) > 0);
  }
}

TEST_CASE("frame source: exact mask equals the label, static frames have none",
          "[frontend][scenario]") {
  const auto sequence = hbos::slam::load_tum_sequence(slam_data("fr1_xyz_37").string());
  hbos::slam::MaskConfig mask;
  mask.source = hbos::slam::MaskSource::kExact;
  hbos::slam::FrameSource dynamic(sequence, 5000.0, person_scenario(), mask);
  const hbos::slam::Frame f = dynamic.frame(3);
  REQUIRE_FALSE(f.person_label.empty());
  CHECK(cv::countNonZero(f.person_label) > 10000);
  CHECK(cv::countNonZero(f.mask != f.person_label) == 0);
  CHECK(f.stamp == sequence.frames[3].rgb.stamp);

  hbos::slam::FrameSource still(sequence, 5000.0, hbos::slam::ScenarioConfig{}, mask);
  const hbos::slam::Frame g = still.frame(3);
  CHECK(g.person_label.empty());
  CHECK(cv::countNonZero(g.mask) == 0);
}
