#include "tum_folder.hpp"

#include "frontend/dataset.hpp"
#include "frontend/person_scenario.hpp"
#include "test_frontend_support.hpp"

#include <fmt/format.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <fstream>

namespace hbos_test {

namespace fs = std::filesystem;

void write_tum_folder(const std::string& dir, int frames) {
  const auto sequence = hbos::slam::load_tum_sequence(slam_data("fr1_xyz_37").string());
  hbos::slam::ScenarioConfig scenario;
  scenario.add_person = true;
  const hbos::slam::PersonCompositor person(
      hbos::slam::load_person_cutout(slam_data("person").string()), scenario);
  for (const char* sub : {"rgb", "depth", "objects", "masks/perfect", "masks/eroded"}) {
    fs::create_directories(fs::path(dir) / sub);
  }
  std::ofstream rgb_list(fs::path(dir) / "rgb.txt"), depth_list(fs::path(dir) / "depth.txt");
  rgb_list << "# timestamp filename\n";
  depth_list << "# timestamp filename\n";
  const cv::Mat disc = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(13, 13));
  for (int i = 0; i < frames; ++i) {
    auto images = hbos::slam::read_frame_images(sequence, i, 5000.0);
    const cv::Mat label = person.composite(i, images.bgr, images.depth_m);
    const std::string stamp =
        fmt::format("{:.6f}", sequence.frames[static_cast<std::size_t>(i)].rgb.stamp);
    const std::string name = stamp + ".png";
    cv::imwrite((fs::path(dir) / "rgb" / name).string(), images.bgr);
    cv::Mat depth;
    images.depth_m.convertTo(depth, CV_16U, 5000.0);
    cv::imwrite((fs::path(dir) / "depth" / name).string(), depth);
    cv::Mat ids;
    cv::compare(label, 0, ids, cv::CMP_NE);
    cv::imwrite((fs::path(dir) / "objects" / name).string(), ids / 255);
    cv::imwrite((fs::path(dir) / "masks" / "perfect" / name).string(), 255 - label);
    cv::Mat eroded;
    cv::erode(label, eroded, disc);
    cv::imwrite((fs::path(dir) / "masks" / "eroded" / name).string(), 255 - eroded);
    rgb_list << stamp << " rgb/" << name << "\n";
    depth_list << stamp << " depth/" << name << "\n";
  }
  fs::copy_file(slam_data("fr1_xyz_37/groundtruth.txt"), fs::path(dir) / "groundtruth.txt",
                fs::copy_options::overwrite_existing);
}

std::string frame_stem(const std::string& dir, int index) {
  const auto list = hbos::slam::read_image_list((fs::path(dir) / "rgb.txt").string());
  return fs::path(list.at(static_cast<std::size_t>(index)).path).stem().string();
}

}  // namespace hbos_test
