// The mask's neighbourhood the front end passes to the screen (frontend/mask_distance.hpp):
// distances to the nearest masked pixel, and the tracker's use of them.

#include <catch2/catch.hpp>

#include "frontend/mask_distance.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <limits>

using hbos::slam::MaskDistance;

TEST_CASE("mask distance: Euclidean distance to the nearest masked pixel", "[frontend][mask]") {
  cv::Mat mask(120, 160, CV_8U, cv::Scalar(0));
  mask(cv::Rect(50, 40, 20, 30)).setTo(255);  // x 50..69, y 40..69
  const MaskDistance d(mask);
  CHECK(d.at({55.f, 50.f}) == 0.0);                        // on the mask
  CHECK(d.at({80.f, 50.f}) == Approx(11.0).margin(0.01));  // 11 px right of column 69
  CHECK(d.at({60.f, 20.f}) == Approx(20.0).margin(0.01));  // 20 px above row 40
  // Diagonal from the corner (69, 69): Euclidean, not city-block.
  CHECK(d.at({72.f, 73.f}) == Approx(5.0).margin(0.05));
  // Rounded to the nearest pixel; outside the image, the nearest pixel inside it.
  CHECK(d.at({79.6f, 50.f}) == d.at({80.f, 50.f}));
  CHECK(d.at({-30.f, 50.f}) == d.at({0.f, 50.f}));
  CHECK(d.at({0.f, 50.f}) == Approx(50.0).margin(0.01));
}

TEST_CASE("mask distance: no masked pixel puts every pixel infinitely far", "[frontend][mask]") {
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(MaskDistance(cv::Mat()).at({10.f, 10.f}) == inf);
  CHECK(MaskDistance(cv::Mat(48, 64, CV_8U, cv::Scalar(0))).at({10.f, 10.f}) == inf);
}

TEST_CASE("mask distance: a mask of the wrong type is refused", "[frontend][mask]") {
  CHECK_THROWS(MaskDistance(cv::Mat(8, 8, CV_32F, cv::Scalar(0))));
}
