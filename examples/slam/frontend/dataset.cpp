#include "frontend/dataset.hpp"

#include "eval/rpe.hpp"
#include "eval/trajectory_io.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace hbos::slam {

std::vector<ListedImage> read_image_list(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InvalidArgument(fmt::format("cannot open image list '{}'", path));
  std::vector<ListedImage> images;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream fields(line);
    std::string stamp_text, file, extra;
    if (!(fields >> stamp_text) || stamp_text[0] == '#') continue;  // blank or comment
    if (!(fields >> file) || (fields >> extra)) {
      throw InvalidArgument(
          fmt::format("{}:{}: expected 'timestamp filename', got \"{}\"", path, number, line));
    }
    char* end = nullptr;
    const double stamp = std::strtod(stamp_text.c_str(), &end);
    if (end != stamp_text.c_str() + stamp_text.size() || !std::isfinite(stamp)) {
      throw InvalidArgument(
          fmt::format("{}:{}: timestamp \"{}\" is not a finite number", path, number, stamp_text));
    }
    if (!images.empty() && !(stamp > images.back().stamp)) {
      throw InvalidArgument(fmt::format("{}:{}: timestamp {} does not increase (line {} has {})",
                                        path, number, stamp_text, images.back().line,
                                        images.back().stamp));
    }
    images.push_back({stamp, file, number});
  }
  if (images.empty()) throw InvalidArgument(fmt::format("{}: lists no image", path));
  return images;
}

std::vector<double> RgbdSequence::rgb_stamps() const {
  std::vector<double> stamps;
  stamps.reserve(frames.size());
  for (const FrameRecord& f : frames) stamps.push_back(f.rgb.stamp);
  return stamps;
}

RgbdSequence load_tum_sequence(const std::string& folder, double max_difference) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(folder)) {
    throw InvalidArgument(fmt::format("dataset folder '{}' does not exist", folder));
  }
  RgbdSequence sequence;
  sequence.root = folder;
  const std::vector<ListedImage> rgb = read_image_list((fs::path(folder) / "rgb.txt").string());
  const std::vector<ListedImage> depth = read_image_list((fs::path(folder) / "depth.txt").string());

  std::vector<double> depth_stamps;
  for (const auto& d : depth) depth_stamps.push_back(d.stamp);
  // Each colour image takes the depth image nearest in time. (associate.py's greedy one-to-one
  // matching would pair 32 of the embedded 37 fr1 frames, not 36: the depth stream runs ~15 ms
  // ahead, so a colour image's successor depth is often only ~18 ms away and gets taken.)
  for (const ListedImage& r : rgb) {
    const auto nearest = static_cast<std::size_t>(find_closest_index(depth_stamps, r.stamp));
    if (std::abs(depth[nearest].stamp - r.stamp) < max_difference) {
      sequence.frames.push_back({r, depth[nearest]});
    }
  }
  sequence.unpaired_rgb = static_cast<Eigen::Index>(rgb.size() - sequence.frames.size());
  if (sequence.frames.empty()) {
    throw InvalidArgument(
        fmt::format("{}: no colour image has a depth image within {} s", folder, max_difference));
  }
  const fs::path gt = fs::path(folder) / "groundtruth.txt";
  if (fs::exists(gt)) sequence.groundtruth = read_tum_trajectory(gt.string());
  return sequence;
}

RgbdImages read_frame_images(const RgbdSequence& sequence, Eigen::Index index,
                             double depth_factor) {
  namespace fs = std::filesystem;
  if (index < 0 || index >= sequence.size()) {
    throw InvalidArgument(fmt::format("frame {} out of range [0, {})", index, sequence.size()));
  }
  const FrameRecord& f = sequence.frames[static_cast<std::size_t>(index)];
  const std::string rgb_path = (fs::path(sequence.root) / f.rgb.path).string();
  const std::string depth_path = (fs::path(sequence.root) / f.depth.path).string();
  if (!fs::is_regular_file(rgb_path)) {
    throw InvalidArgument(
        fmt::format("colour image '{}' (rgb.txt:{}) does not exist", rgb_path, f.rgb.line));
  }
  if (!fs::is_regular_file(depth_path)) {
    throw InvalidArgument(
        fmt::format("depth image '{}' (depth.txt:{}) does not exist", depth_path, f.depth.line));
  }
  RgbdImages images;
  images.bgr = cv::imread(rgb_path, cv::IMREAD_COLOR);
  if (images.bgr.empty()) {
    throw InvalidArgument(
        fmt::format("cannot read colour image '{}' (rgb.txt:{})", rgb_path, f.rgb.line));
  }
  const cv::Mat raw_depth = cv::imread(depth_path, cv::IMREAD_UNCHANGED);
  if (raw_depth.empty()) {
    throw InvalidArgument(
        fmt::format("cannot read depth image '{}' (depth.txt:{})", depth_path, f.depth.line));
  }
  if (raw_depth.type() != CV_16UC1) {
    throw InvalidArgument(fmt::format(
        "depth image '{}' (depth.txt:{}) is not 16-bit single channel", depth_path, f.depth.line));
  }
  if (raw_depth.size() != images.bgr.size()) {
    throw InvalidArgument(fmt::format("depth image '{}' is {}x{}, its colour image '{}' {}x{}",
                                      depth_path, raw_depth.cols, raw_depth.rows, rgb_path,
                                      images.bgr.cols, images.bgr.rows));
  }
  raw_depth.convertTo(images.depth_m, CV_32F, 1.0 / depth_factor);
  return images;
}

}  // namespace hbos::slam
