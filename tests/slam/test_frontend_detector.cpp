// The built-in dynamic-object prior: Yolo-Fastest finds the people on the real fr3/walking_xyz
// frame, where DynaSLAM's mask marks them.

#include <catch2/catch.hpp>

#include "frontend/person_detector.hpp"
#include "frontend/person_mask.hpp"
#include "test_frontend_support.hpp"

#include <hbos/error.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

using Catch::Matchers::Contains;
using hbos_test::slam_data;

namespace {

double iou(const cv::Rect& a, const cv::Rect& b) {
  const double inter = (a & b).area();
  return inter / (a.area() + b.area() - inter);
}

hbos::slam::MaskConfig detector_config() {
  hbos::slam::MaskConfig c;
  c.source = hbos::slam::MaskSource::kDetector;
  c.detector_dir = slam_data("models/yolo-fastest-1.1_body").string();
  return c;
}

}  // namespace

TEST_CASE("detector: every person of the real fr3 frame gets a box with IoU > 0.5",
          "[frontend][detector]") {
  const cv::Mat frame = cv::imread(slam_data("person/source_frame.jpg").string(), cv::IMREAD_COLOR);
  const cv::Mat static_mask =
      cv::imread(slam_data("person/source_mask.png").string(), cv::IMREAD_UNCHANGED);
  REQUIRE_FALSE(frame.empty());
  REQUIRE(static_mask.type() == CV_8UC1);

  hbos::slam::PersonDetector detector(detector_config());
  const auto boxes = detector.detect(frame);
  REQUIRE_FALSE(boxes.empty());

  // The mask's people (0 = person): one connected region each, the two people of the frame.
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(static_mask == 0, labels, stats, centroids);
  int people = 0;
  for (int i = 1; i < n; ++i) {
    if (stats.at<int>(i, cv::CC_STAT_AREA) < 5000) continue;
    ++people;
    const cv::Rect person(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                          stats.at<int>(i, cv::CC_STAT_WIDTH),
                          stats.at<int>(i, cv::CC_STAT_HEIGHT));
    double best = 0.0;
    for (const auto& b : boxes) best = std::max(best, iou(b.box, person));
    INFO("person " << i << " at " << person << ", best IoU " << best);
    CHECK(best > 0.5);
  }
  CHECK(people == 2);
  for (const auto& b : boxes) {
    CHECK(b.confidence >= 0.5f);
    CHECK(b.box.area() > 0);
  }

  // Filled into a mask, the boxes cover most of the people.
  const cv::Mat mask = hbos::slam::boxes_to_mask(boxes, frame.size());
  const int person_pixels = cv::countNonZero(static_mask == 0);
  CHECK(cv::countNonZero(mask & (static_mask == 0)) > 0.8 * person_pixels);
}

TEST_CASE("detector: a missing model is named", "[frontend][detector]") {
  hbos::slam::MaskConfig c = detector_config();
  c.detector_dir = "/nonexistent/models";
  CHECK_THROWS_WITH(
      hbos::slam::PersonDetector(c),
      Contains("/nonexistent/models/yolo-fastest-1.1_body.cfg") && Contains("not found"));
}

TEST_CASE("detector: truncated weights are refused, not read as zeros", "[frontend][detector]") {
  namespace fs = std::filesystem;
  const fs::path model = slam_data("models/yolo-fastest-1.1_body");
  const fs::path dir = fs::temp_directory_path() / "hbos_detector_truncated";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(model / "yolo-fastest-1.1_body.cfg", dir / "yolo-fastest-1.1_body.cfg");
  const fs::path weights = dir / "yolo-fastest-1.1_body.weights";
  std::ifstream in(model / "yolo-fastest-1.1_body.weights", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  hbos::slam::MaskConfig c = detector_config();
  c.detector_dir = dir.string();
  // The whole file loads; a file one weight short, or cut after the header, does not (OpenCV
  // read both without a word, and the short one made the detector find people in noise).
  for (const std::size_t size : {bytes.size(), bytes.size() - 4, std::size_t{100000}}) {
    std::ofstream(weights, std::ios::binary | std::ios::trunc)
        .write(bytes.data(), static_cast<long>(size));
    if (size == bytes.size()) {
      CHECK_NOTHROW(hbos::slam::PersonDetector(c));
    } else {
      CHECK_THROWS_WITH(hbos::slam::PersonDetector(c),
                        Contains("are truncated: " + std::to_string(size) + " bytes") &&
                            Contains("needs " + std::to_string(bytes.size())));
    }
  }
  fs::remove_all(dir);
}
