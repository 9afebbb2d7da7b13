// hbos-slam-prepare-data: builds the data embedded in examples/slam/data from the shared, real
// TUM material, so that what is in the repository can be regenerated and checked:
//  - fr1_xyz_37/: the 37 TUM fr1/xyz frames, colour re-encoded as JPEG quality 95, depth PNGs
//    copied as they are, the lists rewritten, the ground truth trimmed to the frames' span +- 1 s;
//  - person/: one person cut out of the fr3/walking_xyz frame 1341846313.592026 (colour, mask
//    255 = person, raw depth), plus that frame (JPEG 95) and its mask for the detector test;
//  - models/yolo-fastest-1.1_body/: the detector's cfg, weights, names and licence.
// The SOURCE.md files next to the data describe origin and licences (written by hand).
//
// Exit codes: 0 success; 2 bad options or unreadable input; 1 output not written.

#include "common/atomic_file.hpp"
#include "eval/trajectory_io.hpp"
#include "frontend/dataset.hpp"

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <hbos/error.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using hbos::InvalidArgument;

constexpr int kJpegQuality = 95;
constexpr double kGroundTruthMargin = 1.0;  // [s] kept before the first and after the last frame

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidArgument(fmt::format("cannot read '{}'", path.string()));
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

void write_image(const fs::path& path, const cv::Mat& image, const std::vector<int>& params = {}) {
  std::vector<unsigned char> bytes;
  if (!cv::imencode(path.extension().string(), image, bytes, params)) {
    throw std::runtime_error(fmt::format("cannot encode '{}'", path.string()));
  }
  hbos::examples::write_file_atomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

cv::Mat read_image(const fs::path& path, int flags) {
  cv::Mat image = cv::imread(path.string(), flags);
  if (image.empty()) throw InvalidArgument(fmt::format("cannot read image '{}'", path.string()));
  return image;
}

std::string stem_of(const std::string& listed) { return fs::path(listed).stem().string(); }

void prepare_fr1(const fs::path& source, const fs::path& out) {
  fs::create_directories(out / "rgb");
  fs::create_directories(out / "depth");
  const auto rgb = hbos::slam::read_image_list((source / "rgb.txt").string());
  const auto depth = hbos::slam::read_image_list((source / "depth.txt").string());

  std::string rgb_list =
      "# color images of TUM rgbd_dataset_freiburg1_xyz, first 37 frames\n"
      "# re-encoded from the original PNGs as JPEG quality 95 (see SOURCE.md)\n"
      "# timestamp filename\n";
  for (const auto& image : rgb) {
    const std::string name = "rgb/" + stem_of(image.path) + ".jpg";
    write_image(out / name, read_image(source / image.path, cv::IMREAD_COLOR),
                {cv::IMWRITE_JPEG_QUALITY, kJpegQuality});
    rgb_list += fmt::format("{} {}\n", stem_of(image.path), name);
  }
  hbos::examples::write_file_atomically(out / "rgb.txt", rgb_list);

  std::string depth_list =
      "# depth maps of TUM rgbd_dataset_freiburg1_xyz, first 37 frames (16-bit PNG, 5000 = 1 m)\n"
      "# copied unchanged\n"
      "# timestamp filename\n";
  for (const auto& image : depth) {
    hbos::examples::write_file_atomically(out / image.path, read_bytes(source / image.path));
    depth_list += fmt::format("{} {}\n", stem_of(image.path), image.path);
  }
  hbos::examples::write_file_atomically(out / "depth.txt", depth_list);

  // Ground truth over the frames' span +- 1 s: enough for association, a fraction of the file.
  const double begin = std::min(rgb.front().stamp, depth.front().stamp) - kGroundTruthMargin;
  const double end = std::max(rgb.back().stamp, depth.back().stamp) + kGroundTruthMargin;
  std::ifstream gt(source / "groundtruth.txt");
  if (!gt)
    throw InvalidArgument(fmt::format("cannot read '{}'", (source / "groundtruth.txt").string()));
  std::string trimmed =
      "# ground truth trajectory of TUM rgbd_dataset_freiburg1_xyz, trimmed to the 37 frames +- 1 "
      "s\n"
      "# timestamp tx ty tz qx qy qz qw\n";
  std::string line;
  while (std::getline(gt, line)) {
    if (line.empty() || line[0] == '#') continue;
    const double stamp = std::stod(line.substr(0, line.find(' ')));
    if (stamp >= begin && stamp <= end) trimmed += line + "\n";
  }
  hbos::examples::write_file_atomically(out / "groundtruth.txt", trimmed);
  // Read back: the trimmed file must still be a valid trajectory.
  static_cast<void>(hbos::slam::read_tum_trajectory((out / "groundtruth.txt").string()));
  std::cout << fmt::format(
      "fr1_xyz_37: {} colour, {} depth frames, ground truth {:.3f} .. {:.3f} s\n", rgb.size(),
      depth.size(), begin, end);
}

// The person nearest to `seed` in the mask (0 = person): its bounding box and its own pixels.
void prepare_person(const fs::path& fr3, const fs::path& out, cv::Point seed) {
  fs::create_directories(out);
  const fs::path rgb_path = fr3 / "rgb" / "1341846313.592026.png";
  const fs::path mask_path = fr3 / "mask" / "1341846313.592026.png";
  const fs::path depth_path = fr3 / "depth" / "1341846313.592088.png";
  const cv::Mat rgb = read_image(rgb_path, cv::IMREAD_COLOR);
  const cv::Mat mask = read_image(mask_path, cv::IMREAD_UNCHANGED);
  const cv::Mat depth = read_image(depth_path, cv::IMREAD_UNCHANGED);
  if (mask.type() != CV_8UC1 || depth.type() != CV_16UC1) {
    throw InvalidArgument("fr3 mask must be 8-bit and depth 16-bit");
  }
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask == 0, labels, stats, centroids, 8, CV_32S);
  int best = 0;
  double best_distance = 1e18;
  for (int i = 1; i < n; ++i) {
    const double d = cv::norm(cv::Point2d(centroids.at<double>(i, 0), centroids.at<double>(i, 1)) -
                              cv::Point2d(seed));
    if (stats.at<int>(i, cv::CC_STAT_AREA) > 1000 && d < best_distance) {
      best = i;
      best_distance = d;
    }
  }
  if (best == 0) throw InvalidArgument("no person found in the fr3 mask");
  const cv::Rect box(stats.at<int>(best, cv::CC_STAT_LEFT), stats.at<int>(best, cv::CC_STAT_TOP),
                     stats.at<int>(best, cv::CC_STAT_WIDTH),
                     stats.at<int>(best, cv::CC_STAT_HEIGHT));
  const cv::Mat person = labels(box) == best;  // 255 on this person only
  cv::Mat depth_crop = depth(box).clone();
  write_image(out / "rgb.png", rgb(box).clone());
  write_image(out / "mask.png", person);
  write_image(out / "depth.png", depth_crop);
  // The whole frame and its mask, for the detector test on a real image.
  write_image(out / "source_frame.jpg", rgb, {cv::IMWRITE_JPEG_QUALITY, kJpegQuality});
  hbos::examples::write_file_atomically(out / "source_mask.png", read_bytes(mask_path));
  std::cout << fmt::format("person: box x {} y {} w {} h {}, {} pixels\n", box.x, box.y, box.width,
                           box.height, cv::countNonZero(person));
}

void prepare_models(const fs::path& models, const fs::path& out) {
  const fs::path body = out / "yolo-fastest-1.1_body";
  fs::create_directories(body);
  for (const char* name :
       {"yolo-fastest-1.1_body.cfg", "yolo-fastest-1.1_body.weights", "body.names"}) {
    hbos::examples::write_file_atomically(body / name,
                                          read_bytes(models / "yolo-fastest-1.1_body" / name));
  }
  hbos::examples::write_file_atomically(out / "LICENSE.darknet-YOLO.txt",
                                        read_bytes(models / "LICENSE.darknet-YOLO.txt"));
  std::cout << "models: yolo-fastest-1.1_body copied\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Builds examples/slam/data from the shared TUM frames and models.",
               "hbos-slam-prepare-data"};
  std::string fr1, fr3, models, out;
  int seed_x = 140, seed_y = 300;
  app.add_option("--fr1", fr1, "folder of the 37 TUM fr1/xyz frames")->required();
  app.add_option("--fr3", fr3, "folder with the fr3/walking_xyz rgb/, mask/, depth/")->required();
  app.add_option("--models", models, "folder with yolo-fastest-1.1_body/")->required();
  app.add_option("--out", out, "examples/slam/data")->required();
  app.add_option("--seed-x", seed_x, "the person nearest this pixel is cut out")
      ->capture_default_str();
  app.add_option("--seed-y", seed_y, "the person nearest this pixel is cut out")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    prepare_fr1(fr1, fs::path(out) / "fr1_xyz_37");
    prepare_person(fr3, fs::path(out) / "person", cv::Point(seed_x, seed_y));
    prepare_models(models, fs::path(out) / "models");
  } catch (const InvalidArgument& e) {
    std::cerr << "hbos-slam-prepare-data: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "hbos-slam-prepare-data: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
