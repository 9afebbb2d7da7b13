// Tests of the optional OpenCV adapter (hbos/screening/opencv.hpp): filling Matches from OpenCV
// types, the mask prior, and filtering matches by a screen's result.

#include <catch2/catch.hpp>

#include <hbos/screening.hpp>
#include <hbos/screening/opencv.hpp>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

#include <vector>

#include "../support/synthetic_scene.hpp"

TEST_CASE("on_mask reads the nearest pixel and ignores points outside", "[opencv]") {
  cv::Mat mask = cv::Mat::zeros(10, 20, CV_8UC1);
  mask.at<unsigned char>(3, 7) = 1;
  CHECK(hbos::on_mask(mask, cv::Point2f(7.2f, 2.8f)));
  CHECK_FALSE(hbos::on_mask(mask, cv::Point2f(8.0f, 3.0f)));
  CHECK_FALSE(hbos::on_mask(mask, cv::Point2f(-5.0f, 3.0f)));
  CHECK_FALSE(hbos::on_mask(mask, cv::Point2f(7.0f, 30.0f)));
  CHECK_FALSE(hbos::on_mask(cv::Mat(), cv::Point2f(7.0f, 3.0f)));
  CHECK_THROWS_WITH(hbos::on_mask(cv::Mat::zeros(10, 20, CV_32FC1), cv::Point2f(1, 1)),
                    Catch::Contains("dynamic mask must be CV_8UC1"));
}

TEST_CASE("fill_matches from DMatch uses queryIdx, trainIdx, octave and the mask", "[opencv]") {
  const std::vector<cv::Point2f> predicted{{10, 10}, {20, 20}, {30, 30}};
  std::vector<cv::KeyPoint> keypoints(2);
  keypoints[0] = cv::KeyPoint(cv::Point2f(31, 30), 31.0f, -1, 0, 3);
  keypoints[1] = cv::KeyPoint(cv::Point2f(10, 12), 31.0f, -1, 0, 0);
  const std::vector<cv::DMatch> matches{cv::DMatch(2, 0, 0.f), cv::DMatch(0, 1, 0.f)};
  cv::Mat mask = cv::Mat::zeros(48, 64, CV_8UC1);
  mask.at<unsigned char>(12, 10) = 255;

  hbos::Matchesd m;
  hbos::fill_matches(predicted, keypoints, matches, m, mask);
  REQUIRE(m.size() == 2);
  CHECK(m.residual(0) == Eigen::Vector2d(1, 0));
  CHECK(m.sigma(0) == Approx(1.728));
  CHECK_FALSE(m.on_dynamic_mask(0));
  CHECK(m.residual(1) == Eigen::Vector2d(0, 2));
  CHECK(m.sigma(1) == 1.0);
  CHECK(m.on_dynamic_mask(1));

  const std::vector<cv::DMatch> bad{cv::DMatch(5, 0, 0.f)};
  CHECK_THROWS_WITH(hbos::fill_matches(predicted, keypoints, bad, m),
                    Catch::Contains("queryIdx 5 out of range"));
  const std::vector<cv::DMatch> bad_train{cv::DMatch(0, 2, 0.f)};
  CHECK_THROWS_WITH(hbos::fill_matches(predicted, keypoints, bad_train, m),
                    Catch::Contains("trainIdx 2 out of range"));
}

TEST_CASE("fill_matches from point pairs, screening and filtering by the result", "[opencv]") {
  hbos_test::SceneConfig config;
  config.seed = 3;
  config.person_share = 0.08;
  config.gross_share = 0.03;
  const hbos_test::Scene scene = hbos_test::make_scene(config);
  std::vector<cv::Point2f> predicted, observed;
  std::vector<cv::DMatch> dmatches;
  for (Eigen::Index i = 0; i < scene.size(); ++i) {
    predicted.emplace_back(static_cast<float>(scene.predicted(0, i)),
                           static_cast<float>(scene.predicted(1, i)));
    observed.emplace_back(static_cast<float>(scene.observed(0, i)),
                          static_cast<float>(scene.observed(1, i)));
    dmatches.emplace_back(static_cast<int>(i), static_cast<int>(i), 0.f);
  }
  hbos::Matchesf m;
  hbos::fill_matches(predicted, observed, m);
  REQUIRE(m.size() == scene.size());
  hbos::ReprojectionScreenf screen(hbos::ChiSquareGate{});
  const auto& result = screen.screen(m);
  const std::vector<cv::DMatch> kept = hbos::kept_matches(dmatches, result);
  CHECK(static_cast<Eigen::Index>(kept.size()) == result.n_inliers());
  for (const auto& d : kept) CHECK(result.inlier(d.queryIdx));
  const std::vector<unsigned char> mask = hbos::inlier_mask(result);
  CHECK(static_cast<Eigen::Index>(cv::countNonZero(mask)) == result.n_inliers());
  // Gross mismatches are not kept.
  for (const auto& d : kept)
    CHECK(scene.label[static_cast<std::size_t>(d.queryIdx)] != hbos_test::Label::GrossMismatch);

  CHECK_THROWS_WITH(hbos::fill_matches(predicted, std::vector<cv::Point2f>(3), m),
                    Catch::Contains("observed has 3"));
  CHECK_THROWS_WITH(hbos::kept_matches(std::vector<cv::DMatch>(2), result),
                    Catch::Contains("were given"));
}
