#include "frontend/mask_files.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <utility>

namespace hbos::slam {

namespace fs = std::filesystem;

namespace {

bool is_image_file(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const std::array<const char*, 8> kExtensions = {".png", ".jpg",  ".jpeg", ".bmp",
                                                         ".tif", ".tiff", ".pgm",  ".ppm"};
  return std::any_of(kExtensions.begin(), kExtensions.end(),
                     [&](const char* e) { return ext == e; });
}

// A stem that is wholly a finite number (TUM names files by their stamp).
std::optional<double> stamp_of(const std::string& stem) {
  if (stem.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(stem.c_str(), &end);
  if (end != stem.c_str() + stem.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// The size from a PNG's IHDR chunk without decoding it (checking ~900 masks up front by decoding
// them would cost about a second); nullopt when the file is not a PNG.
std::optional<cv::Size> png_size(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<unsigned char, 24> head{};
  if (!in.read(reinterpret_cast<char*>(head.data()), head.size())) return std::nullopt;
  static const std::array<unsigned char, 8> kSignature = {0x89, 'P',  'N',  'G',
                                                          '\r', '\n', 0x1a, '\n'};
  if (!std::equal(kSignature.begin(), kSignature.end(), head.begin())) return std::nullopt;
  if (head[12] != 'I' || head[13] != 'H' || head[14] != 'D' || head[15] != 'R') return std::nullopt;
  const auto be32 = [&](std::size_t at) {
    return (static_cast<unsigned long>(head[at]) << 24) |
           (static_cast<unsigned long>(head[at + 1]) << 16) |
           (static_cast<unsigned long>(head[at + 2]) << 8) |
           static_cast<unsigned long>(head[at + 3]);
  };
  return cv::Size(static_cast<int>(be32(16)), static_cast<int>(be32(20)));
}

cv::Size image_size(const std::string& path, const std::string& what) {
  if (const auto s = png_size(path)) return *s;
  const cv::Mat image = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (image.empty()) throw InvalidArgument(fmt::format("cannot read {} '{}'", what, path));
  return image.size();
}

}  // namespace

const char* to_string(MaskConvention convention) {
  return convention == MaskConvention::kDynaSlam ? "dynaslam" : "nonzero-dynamic";
}

MaskConvention parse_mask_convention(const std::string& name) {
  if (name == "dynaslam") return MaskConvention::kDynaSlam;
  if (name == "nonzero-dynamic") return MaskConvention::kNonzeroDynamic;
  throw InvalidArgument("mask convention '" + name + "' is not one of dynaslam, nonzero-dynamic");
}

FrameImageFiles::FrameImageFiles(const RgbdSequence& sequence, const std::string& dir,
                                 double max_difference, const std::string& what)
    : what_(what) {
  if (!fs::is_directory(dir)) {
    throw InvalidArgument(fmt::format("{} folder '{}' does not exist", what, dir));
  }
  if (sequence.frames.empty()) throw InvalidArgument("the sequence has no frame");
  // Index the folder once: by stem, and by stamp for the stems that are numbers.
  std::map<std::string, std::string> by_stem;
  std::vector<std::pair<double, std::string>> by_stamp;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (!entry.is_regular_file() || !is_image_file(entry.path())) continue;
    const std::string stem = entry.path().stem().string();
    by_stem.emplace(stem, entry.path().string());
    if (const auto t = stamp_of(stem)) by_stamp.emplace_back(*t, entry.path().string());
  }
  if (by_stem.empty()) throw InvalidArgument(fmt::format("{} folder '{}' has no image", what, dir));
  std::sort(by_stamp.begin(), by_stamp.end());

  const FrameRecord& first = sequence.frames.front();
  const std::string first_rgb = (fs::path(sequence.root) / first.rgb.path).string();
  size_ = image_size(first_rgb, "colour image");

  paths_.reserve(sequence.frames.size());
  for (std::size_t i = 0; i < sequence.frames.size(); ++i) {
    const ListedImage& rgb = sequence.frames[i].rgb;
    const std::string stem = fs::path(rgb.path).stem().string();
    std::string found;
    if (const auto it = by_stem.find(stem); it != by_stem.end()) {
      found = it->second;
    } else if (!by_stamp.empty()) {
      const auto after = std::lower_bound(
          by_stamp.begin(), by_stamp.end(), rgb.stamp,
          [](const std::pair<double, std::string>& e, double t) { return e.first < t; });
      auto nearest = after;
      if (after == by_stamp.end() ||
          (after != by_stamp.begin() &&
           std::abs(std::prev(after)->first - rgb.stamp) < std::abs(after->first - rgb.stamp))) {
        nearest = std::prev(after);
      }
      if (std::abs(nearest->first - rgb.stamp) < max_difference) found = nearest->second;
    }
    if (found.empty()) {
      throw InvalidArgument(fmt::format(
          "no {} for frame {} ('{}', rgb.txt:{}) in '{}': no image named '{}.*' and none named "
          "by a timestamp within {} s of {:.6f}",
          what, i, rgb.path, rgb.line, dir, stem, max_difference, rgb.stamp));
    }
    const cv::Size s = image_size(found, what);
    if (s != size_) {
      throw InvalidArgument(fmt::format("{} '{}' is {}x{}, expected {}x{} (the size of '{}')", what,
                                        found, s.width, s.height, size_.width, size_.height,
                                        first_rgb));
    }
    paths_.push_back(std::move(found));
  }
}

const std::string& FrameImageFiles::path(int index) const {
  if (index < 0 || index >= size()) {
    throw InvalidArgument(fmt::format("{} of frame {} out of range [0, {})", what_, index, size()));
  }
  return paths_[static_cast<std::size_t>(index)];
}

cv::Mat FrameImageFiles::read(int index) const {
  const std::string& p = path(index);
  cv::Mat image = cv::imread(p, cv::IMREAD_UNCHANGED);
  if (image.empty()) throw InvalidArgument(fmt::format("cannot read {} '{}'", what_, p));
  if (image.size() != size_) {
    throw InvalidArgument(fmt::format("{} '{}' is {}x{}, expected {}x{}", what_, p, image.cols,
                                      image.rows, size_.width, size_.height));
  }
  if (image.channels() == 1) return image;
  // Non-zero where any channel is (a colour-coded mask): the channels' maximum.
  std::vector<cv::Mat> channels;
  cv::split(image, channels);
  cv::Mat any = channels[0];
  for (std::size_t c = 1; c < channels.size(); ++c) any = cv::max(any, channels[c]);
  return any;
}

MaskFiles::MaskFiles(const RgbdSequence& sequence, const std::string& dir,
                     MaskConvention convention, double max_difference)
    : files_(sequence, dir, max_difference, "mask"), convention_(convention) {}

cv::Mat MaskFiles::mask(int index) const {
  const cv::Mat stored = files_.read(index);
  cv::Mat dynamic;
  // compare() gives 255 where the condition holds, the front end's mask value.
  cv::compare(stored, 0, dynamic,
              convention_ == MaskConvention::kDynaSlam ? cv::CMP_EQ : cv::CMP_NE);
  return dynamic;
}

ObjectLabels::ObjectLabels(const RgbdSequence& sequence, const std::string& dir,
                           double max_difference)
    : files_(sequence, dir, max_difference, "object-id image") {}

cv::Mat ObjectLabels::label(int index) const {
  cv::Mat on_object;
  cv::compare(files_.read(index), 0, on_object, cv::CMP_NE);
  return on_object;
}

std::string default_objects_dir(const RgbdSequence& sequence) {
  const fs::path dir = fs::path(sequence.root) / "objects";
  return fs::is_directory(dir) ? dir.string() : std::string();
}

}  // namespace hbos::slam
