#include "frontend/person_scenario.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <utility>
#include <vector>

namespace hbos::slam {

namespace {

cv::Mat read_image(const std::string& path, int flags, int expected_type, const char* what) {
  if (!std::filesystem::is_regular_file(path)) {
    throw InvalidArgument(fmt::format("{} '{}' does not exist", what, path));
  }
  cv::Mat image = cv::imread(path, flags);
  if (image.empty()) throw InvalidArgument(fmt::format("cannot read {} '{}'", what, path));
  if (image.type() != expected_type) {
    throw InvalidArgument(fmt::format("{} '{}' has the wrong pixel type", what, path));
  }
  return image;
}

}  // namespace

PersonCutout load_person_cutout(const std::string& folder) {
  namespace fs = std::filesystem;
  const auto file = [&](const char* name) { return (fs::path(folder) / name).string(); };
  PersonCutout cutout;
  cutout.bgr = read_image(file("rgb.png"), cv::IMREAD_COLOR, CV_8UC3, "person colour image");
  cutout.mask = read_image(file("mask.png"), cv::IMREAD_UNCHANGED, CV_8UC1, "person mask");
  const cv::Mat raw =
      read_image(file("depth.png"), cv::IMREAD_UNCHANGED, CV_16UC1, "person depth image");
  if (cutout.mask.size() != cutout.bgr.size() || raw.size() != cutout.bgr.size()) {
    throw InvalidArgument(
        fmt::format("person cut-out in '{}': rgb.png, mask.png and depth.png "
                    "differ in size",
                    folder));
  }
  // Depth relative to the person's median keeps the body's shape when it is moved closer.
  std::vector<float> on_person;
  for (int y = 0; y < raw.rows; ++y) {
    for (int x = 0; x < raw.cols; ++x) {
      if (cutout.mask.at<std::uint8_t>(y, x) != 0 && raw.at<std::uint16_t>(y, x) != 0) {
        on_person.push_back(static_cast<float>(raw.at<std::uint16_t>(y, x)));
      }
    }
  }
  if (on_person.empty()) {
    throw InvalidArgument(
        fmt::format("person mask '{}' has no pixel with depth", file("mask.png")));
  }
  const auto middle = on_person.begin() + static_cast<std::ptrdiff_t>(on_person.size() / 2);
  std::nth_element(on_person.begin(), middle, on_person.end());
  raw.convertTo(cutout.relative_depth, CV_32F, 1.0 / static_cast<double>(*middle));
  return cutout;
}

PersonCompositor::PersonCompositor(PersonCutout cutout, ScenarioConfig config)
    : cutout_(std::move(cutout)), config_(std::move(config)) {
  if (!(config_.depth_m > 0.0) || !std::isfinite(config_.depth_m)) {
    throw InvalidArgument(
        fmt::format("person depth must be finite and > 0 m, got {}", config_.depth_m));
  }
  // Bounded so that pixel positions stay far from integer overflow on any sequence length.
  if (!(std::abs(config_.start_x_px) <= 1e5) || !(std::abs(config_.speed_px_per_frame) <= 1e3)) {
    throw InvalidArgument(fmt::format(
        "person start {} px must lie in [-1e5, 1e5] and speed {} px/frame in [-1e3, 1e3]",
        config_.start_x_px, config_.speed_px_per_frame));
  }
}

cv::Point PersonCompositor::position(int index, cv::Size image) const {
  const double x = config_.start_x_px + config_.speed_px_per_frame * index;
  return {static_cast<int>(std::lround(x)), image.height - cutout_.bgr.rows};
}

cv::Mat PersonCompositor::composite(int index, cv::Mat& bgr, cv::Mat& depth_m) const {
  cv::Mat label(bgr.size(), CV_8UC1, cv::Scalar(0));
  const cv::Point origin = position(index, bgr.size());
  const cv::Rect placed =
      cv::Rect(origin, cutout_.bgr.size()) & cv::Rect(cv::Point(0, 0), bgr.size());
  const auto depth = static_cast<float>(config_.depth_m);
  for (int y = placed.y; y < placed.y + placed.height; ++y) {
    for (int x = placed.x; x < placed.x + placed.width; ++x) {
      const int u = x - origin.x, v = y - origin.y;
      if (cutout_.mask.at<std::uint8_t>(v, u) == 0) continue;
      bgr.at<cv::Vec3b>(y, x) = cutout_.bgr.at<cv::Vec3b>(v, u);
      // A hole in the cut-out's depth stays a hole: the sensor saw nothing there either.
      depth_m.at<float>(y, x) = cutout_.relative_depth.at<float>(v, u) * depth;
      label.at<std::uint8_t>(y, x) = 255;
    }
  }
  return label;
}

}  // namespace hbos::slam
