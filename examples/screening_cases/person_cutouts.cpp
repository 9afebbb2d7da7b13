#include "person_cutouts.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdint>
#include <filesystem>

namespace hbos::cases {

namespace {

// The one fr3/walking_xyz frame with raw colour, raw depth and DynaSLAM's mask (SOURCE.md there).
constexpr const char* kColour = "rgb/1341846313.592026.png";
constexpr const char* kMask = "mask/1341846313.592026.png";
constexpr const char* kDepth = "depth/1341846313.592088.png";

cv::Mat read(const std::filesystem::path& path, int type) {
  if (!std::filesystem::is_regular_file(path)) {
    throw InvalidArgument(fmt::format("fr3 image '{}' does not exist", path.string()));
  }
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  if (image.empty()) throw InvalidArgument(fmt::format("cannot read '{}'", path.string()));
  if (image.type() != type) {
    throw InvalidArgument(fmt::format("fr3 image '{}' has pixel type {}, expected {}",
                                      path.string(), image.type(), type));
  }
  return image;
}

}  // namespace

std::vector<SourcePerson> cut_people(const std::string& fr3_folder, int min_pixels) {
  const std::filesystem::path root(fr3_folder);
  const cv::Mat bgr = read(root / kColour, CV_8UC3);
  const cv::Mat mask = read(root / kMask, CV_8UC1);
  const cv::Mat depth = read(root / kDepth, CV_16UC1);
  if (mask.size() != bgr.size() || depth.size() != bgr.size()) {
    throw InvalidArgument(
        fmt::format("fr3 frame in '{}': colour, mask and depth differ in size", fr3_folder));
  }
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask == 0, labels, stats, centroids, 8, CV_32S);
  std::vector<SourcePerson> people;
  for (int i = 1; i < n; ++i) {
    if (stats.at<int>(i, cv::CC_STAT_AREA) < min_pixels) continue;
    SourcePerson p;
    p.box = cv::Rect(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                     stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT));
    p.pixels = stats.at<int>(i, cv::CC_STAT_AREA);
    p.cut.bgr = bgr(p.box).clone();
    p.cut.mask = labels(p.box) == i;  // 255 on this person only
    const cv::Mat raw = depth(p.box);
    std::vector<std::uint16_t> on_person;
    for (int y = 0; y < raw.rows; ++y)
      for (int x = 0; x < raw.cols; ++x)
        if (p.cut.mask.at<std::uint8_t>(y, x) != 0 && raw.at<std::uint16_t>(y, x) != 0)
          on_person.push_back(raw.at<std::uint16_t>(y, x));
    if (on_person.empty()) continue;  // no depth: cannot be placed at a depth
    const auto middle = on_person.begin() + static_cast<std::ptrdiff_t>(on_person.size() / 2);
    std::nth_element(on_person.begin(), middle, on_person.end());
    p.median_depth_m = static_cast<double>(*middle) / 5000.0;
    raw.convertTo(p.cut.relative_depth, CV_32F, 1.0 / static_cast<double>(*middle));
    people.push_back(std::move(p));
  }
  if (people.empty()) {
    throw InvalidArgument(fmt::format("no person region of >= {} pixels with depth in '{}'",
                                      min_pixels, (root / kMask).string()));
  }
  std::sort(people.begin(), people.end(),
            [](const SourcePerson& a, const SourcePerson& b) { return a.box.x < b.box.x; });
  for (std::size_t k = 0; k < people.size(); ++k) people[k].id = static_cast<char>('A' + k);
  return people;
}

}  // namespace hbos::cases
