#include "render/textures.hpp"

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/image_encoding.hpp"
#include "render/trajectory.hpp"

#ifndef HBOS_RENDER_DATA_DIR
#error "HBOS_RENDER_DATA_DIR must be defined by the build"
#endif

namespace hbos::render {

std::filesystem::path default_data_dir() { return HBOS_RENDER_DATA_DIR; }

namespace {

cv::Mat load(const std::filesystem::path& dir, const std::string& file) {
  const auto path = dir / "textures" / file;
  // libjpeg decodes a truncated JPEG with a warning and grey rows: the room would be rendered
  // with them, every frame, without a word.
  // The bytes are read once: checked, then decoded (imdecode runs imread's decoder on them).
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open texture image " + path.string());
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError("read error in texture image " + path.string());
  if (const std::string why = examples::incomplete_encoding(bytes); !why.empty())
    throw InputError("texture image " + path.string() + " " + why);
  cv::Mat m = cv::imdecode(bytes, cv::IMREAD_COLOR);
  if (m.empty()) throw InputError("cannot decode texture image " + path.string());
  return m;
}

}  // namespace

TextureLibrary::TextureLibrary(const std::filesystem::path& dir) {
  const cv::Mat fr3 = load(dir, "fr3_walking_xyz_1341846313.592026.jpg");
  const cv::Mat fr1 = load(dir, "fr1_xyz_1305031102.175304.jpg");
  const cv::Mat hall1 = load(dir, "slambook2_ch11_1.jpg");
  const cv::Mat hall3 = load(dir, "slambook2_ch11_3.jpg");
  const cv::Mat hall7 = load(dir, "slambook2_ch11_7.jpg");
  const cv::Mat hall5 = load(dir, "slambook2_ch11_5.jpg");
  auto crop = [](const cv::Mat& m, int x, int y, int w, int h) {
    return m(cv::Rect(x, y, w, h)).clone();
  };

  // Room: whole frames as wall murals (rich, real texture; frames without people, so no
  // static "person" hangs on a wall), floor and desk crops.
  images_["wall_front"] = hall3.clone();
  images_["wall_left"] = hall5.clone();
  images_["wall_right"] = hall7.clone();
  images_["wall_back"] = hall1.clone();
  images_["floor"] = crop(hall5, 180, 380, 250, 100);
  images_["ceiling"] = crop(hall3, 0, 0, 640, 60);
  images_["desk_top"] = fr1.clone();
  images_["desk_side"] = crop(fr3, 140, 225, 150, 40);
  images_["dark"] = crop(fr3, 195, 200, 55, 50);
  images_["monitor"] = crop(fr3, 178, 188, 90, 82);
  images_["table2_top"] = crop(hall1, 0, 150, 640, 240);
  images_["shelf"] = crop(fr3, 280, 135, 75, 120);
  images_["chair"] = crop(fr3, 400, 325, 85, 60);
  images_["cardboard"] = crop(hall1, 270, 5, 75, 35);
  images_["partition"] = crop(fr3, 100, 120, 400, 160);
  // The carried object: a box wrapped in the blue book's cover from ch11/7.
  images_["carried"] = crop(hall7, 335, 288, 75, 60);

  // People: the two men of fr3/walking_xyz frame 1341846313.592026, cut inside their silhouettes.
  images_["plaid_shirt"] = crop(fr3, 540, 110, 90, 190);
  images_["jeans"] = crop(fr3, 495, 360, 100, 110);
  images_["hair"] = crop(fr3, 495, 15, 60, 50);
  images_["skin"] = crop(fr3, 492, 195, 28, 85);
  images_["black_tee"] = crop(fr3, 60, 205, 70, 125);
  images_["camo"] = crop(fr3, 125, 322, 105, 65);
  images_["face"] = crop(fr3, 98, 125, 50, 75);
  images_["dark_hair"] = crop(fr3, 100, 120, 40, 18);
  images_["shin"] = crop(fr3, 180, 400, 38, 60);
  images_["shoe"] = crop(fr3, 180, 450, 40, 25);
}

cv::Mat TextureLibrary::side_by_side(const cv::Mat& a, const cv::Mat& b, float& split) {
  cv::Mat br;
  const int w = std::max(1, b.cols * a.rows / std::max(1, b.rows));
  cv::resize(b, br, cv::Size(w, a.rows), 0, 0, cv::INTER_AREA);
  cv::Mat out;
  cv::hconcat(a, br, out);
  split = static_cast<float>(a.cols) / static_cast<float>(out.cols);
  return out;
}

}  // namespace hbos::render
