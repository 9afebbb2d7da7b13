// The mask's neighbourhood the front end passes to the screen (frontend/mask_distance.hpp):
// distances to the nearest masked pixel up to the evidence's reach, checked against OpenCV's
// exact Euclidean distance transform.

#include <catch2/catch.hpp>

#include "frontend/config.hpp"
#include "frontend/mask_distance.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <limits>
#include <random>

using hbos::slam::MaskDistance;

namespace {
const double kInf = std::numeric_limits<double>::infinity();
}

TEST_CASE("mask distance: Euclidean distance to the nearest masked pixel", "[frontend][mask]") {
  cv::Mat mask(120, 160, CV_8U, cv::Scalar(0));
  mask(cv::Rect(50, 40, 20, 30)).setTo(255);  // x 50..69, y 40..69
  const MaskDistance d(mask, 64.0);
  CHECK(d.at({55.f, 50.f}) == 0.0);                        // on the mask
  CHECK(d.at({80.f, 50.f}) == Approx(11.0).margin(1e-9));  // 11 px right of column 69
  CHECK(d.at({60.f, 20.f}) == Approx(20.0).margin(1e-9));  // 20 px above row 40
  // Diagonal from the corner (69, 69): Euclidean, not city-block.
  CHECK(d.at({72.f, 73.f}) == Approx(5.0).margin(1e-9));
  // Rounded to the nearest pixel; outside the image, the nearest pixel inside it.
  CHECK(d.at({79.6f, 50.f}) == d.at({80.f, 50.f}));
  CHECK(d.at({-30.f, 50.f}) == d.at({0.f, 50.f}));
  CHECK(d.at({0.f, 50.f}) == Approx(50.0).margin(1e-9));
}

TEST_CASE("mask distance: beyond the reach a pixel is infinitely far", "[frontend][mask]") {
  cv::Mat mask(120, 160, CV_8U, cv::Scalar(0));
  mask(cv::Rect(50, 40, 20, 30)).setTo(255);
  const MaskDistance d(mask, 10.0);
  CHECK(d.at({79.f, 50.f}) == Approx(10.0).margin(1e-9));  // exactly at the reach
  CHECK(d.at({80.f, 50.f}) == kInf);
  CHECK(d.at({77.f, 77.f}) == kInf);  // sqrt(128) = 11.3: inside the square, beyond the reach
  CHECK(MaskDistance(mask, 0.0).at({55.f, 50.f}) == 0.0);
  CHECK(MaskDistance(mask, 0.0).at({70.f, 50.f}) == kInf);
}

TEST_CASE("mask distance: the same as OpenCV's exact distance transform within the reach",
          "[frontend][mask]") {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    cv::Mat mask(96, 128, CV_8U, cv::Scalar(0));
    std::uniform_int_distribution<int> x(0, 127), y(0, 95), r(1, 12);
    for (int blob = 0; blob < 1 + trial % 4; ++blob)
      cv::circle(mask, {x(rng), y(rng)}, r(rng), cv::Scalar(255), cv::FILLED);
    cv::Mat unmasked, reference;
    cv::compare(mask, 0, unmasked, cv::CMP_EQ);
    cv::distanceTransform(unmasked, reference, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
    const double reach = 12.5;
    const MaskDistance d(mask, reach);
    for (int v = 0; v < mask.rows; v += 3) {
      for (int u = 0; u < mask.cols; u += 3) {
        const double expected = reference.at<float>(v, u);
        const double got = d.at({static_cast<float>(u), static_cast<float>(v)});
        INFO("trial " << trial << " pixel (" << u << ", " << v << ")");
        if (expected <= reach - 1e-3) {
          CHECK(got == Approx(expected).margin(1e-3));
        } else if (expected > reach + 1e-3) {
          CHECK(got == kInf);
        }
      }
    }
  }
}

TEST_CASE("mask distance: no masked pixel puts every pixel infinitely far", "[frontend][mask]") {
  CHECK(MaskDistance(cv::Mat(), 10.0).at({10.f, 10.f}) == kInf);
  CHECK(MaskDistance(cv::Mat(48, 64, CV_8U, cv::Scalar(0)), 10.0).at({10.f, 10.f}) == kInf);
}

TEST_CASE("mask distance: a mask of the wrong type or a negative reach is refused",
          "[frontend][mask]") {
  CHECK_THROWS(MaskDistance(cv::Mat(8, 8, CV_32F, cv::Scalar(0)), 10.0));
  CHECK_THROWS(MaskDistance(cv::Mat(8, 8, CV_8U, cv::Scalar(0)), -1.0));
}

TEST_CASE("mask distance: passed only to a screen that reads it", "[frontend][mask]") {
  hbos::slam::Config c;
  c.mask.source = hbos::slam::MaskSource::kDegraded;
  c.screen.mask_evidence = true;
  c.screen.select("default");
  CHECK(hbos::slam::mask_evidence_reach_px(c) == 10.0);
  c.screen.mask_evidence = false;
  CHECK(hbos::slam::mask_evidence_reach_px(c) == 0.0);
  c.screen.mask_evidence = true;
  for (const char* baseline : {"chi2", "fixed", "quantile", "mad", "magnitude", "paper", "none"}) {
    c.screen.select(baseline);
    INFO(baseline);
    CHECK(hbos::slam::mask_evidence_reach_px(c) == 0.0);
  }
  c.screen.select("default");
  c.mask.source = hbos::slam::MaskSource::kNone;
  CHECK(hbos::slam::mask_evidence_reach_px(c) == 0.0);
}
