#include "frontend/dataset.hpp"

#include "common/image_encoding.hpp"
#include "eval/rpe.hpp"
#include "eval/trajectory_io.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace hbos::slam {

namespace {

/// Throws unless `path` names a regular file that can be opened for reading; `what` (e.g.
/// "colour image 'x.png' (rgb.txt:7)") names it.
void require_readable(const std::string& path, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::is_directory(path, error)) throw InvalidArgument(what + " is a directory");
  if (!fs::exists(path, error)) throw InvalidArgument(what + " does not exist");
  if (!fs::is_regular_file(path, error)) throw InvalidArgument(what + " is not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidArgument(what + " cannot be opened: " + std::strerror(errno));
}

std::vector<unsigned char> read_bytes(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidArgument(what + " cannot be opened: " + std::strerror(errno));
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  if (in.bad()) throw InvalidArgument(what + ": read error");
  return bytes;
}

/// Decodes an image file, refusing incomplete JPEG and PNG files. `colour`: IMREAD_COLOR scales a
/// 16-bit PNG to 8 bits without a word, so a depth map listed in rgb.txt is refused instead.
cv::Mat decode_image(const std::string& path, int flags, const std::string& what,
                     bool colour = false) {
  const std::vector<unsigned char> bytes = read_bytes(path, what);
  if (bytes.empty()) throw InvalidArgument(what + " is empty");
  if (const std::string why = examples::incomplete_encoding(bytes); !why.empty()) {
    throw InvalidArgument(what + " " + why);
  }
  if (const int bits = examples::png_bit_depth(bytes); colour && bits > 8) {
    throw InvalidArgument(fmt::format(
        "{} is a {}-bit PNG, not an 8-bit colour image (a depth map listed in rgb.txt?)", what,
        bits));
  }
  cv::Mat image = cv::imdecode(bytes, flags);
  if (image.empty()) throw InvalidArgument(what + " cannot be decoded as an image");
  return image;
}

std::string colour_name(const std::string& path, const ListedImage& image) {
  return fmt::format("colour image '{}' (rgb.txt:{})", path, image.line);
}

std::string depth_name(const std::string& path, const ListedImage& image) {
  return fmt::format("depth image '{}' (depth.txt:{})", path, image.line);
}

}  // namespace

std::vector<ListedImage> read_image_list(const std::string& path) {
  {
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
      throw InvalidArgument(fmt::format("image list '{}' is a directory", path));
    }
  }
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

void check_sequence_files(const RgbdSequence& sequence, Eigen::Index frames) {
  namespace fs = std::filesystem;
  const Eigen::Index n = frames > 0 ? std::min(frames, sequence.size()) : sequence.size();
  for (Eigen::Index i = 0; i < n; ++i) {
    const FrameRecord& f = sequence.frames[static_cast<std::size_t>(i)];
    const std::string rgb_path = (fs::path(sequence.root) / f.rgb.path).string();
    const std::string depth_path = (fs::path(sequence.root) / f.depth.path).string();
    require_readable(rgb_path, colour_name(rgb_path, f.rgb));
    require_readable(depth_path, depth_name(depth_path, f.depth));
  }
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
  const std::string rgb_label = colour_name(rgb_path, f.rgb);
  const std::string depth_label = depth_name(depth_path, f.depth);
  require_readable(rgb_path, rgb_label);
  require_readable(depth_path, depth_label);
  RgbdImages images;
  images.bgr = decode_image(rgb_path, cv::IMREAD_COLOR, rgb_label, /*colour=*/true);
  const cv::Mat raw_depth = decode_image(depth_path, cv::IMREAD_UNCHANGED, depth_label);
  if (raw_depth.type() != CV_16UC1) {
    throw InvalidArgument(fmt::format(
        "depth image '{}' (depth.txt:{}) is not 16-bit single channel", depth_path, f.depth.line));
  }
  if (raw_depth.size() != images.bgr.size()) {
    throw InvalidArgument(fmt::format("{} is {}x{}, its {} {}x{}", depth_label, raw_depth.cols,
                                      raw_depth.rows, rgb_label, images.bgr.cols, images.bgr.rows));
  }
  raw_depth.convertTo(images.depth_m, CV_32F, 1.0 / depth_factor);
  return images;
}

}  // namespace hbos::slam
