// The front end's input: TUM lists and sequences, camera presets and files, and the command's
// handling of bad input (a clear message naming file:line or the option, exit status 2).

#include <catch2/catch.hpp>

#include "frontend/camera.hpp"
#include "frontend/dataset.hpp"
#include "frontend/slam_command.hpp"
#include "test_frontend_support.hpp"

#include <hbos/error.hpp>

#include <opencv2/calib3d.hpp>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

using Catch::Matchers::Contains;
using hbos_test::ScratchDir;
using hbos_test::slam_data;

namespace {

const char* kListHeader = "# color images\n# timestamp filename\n";

int run_command(const std::vector<std::string>& args, std::string& out, std::string& err) {
  std::vector<const char*> argv = {"hbos-slam"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  std::ostringstream o, e;
  const int code = hbos::slam::run_slam_command(static_cast<int>(argv.size()), argv.data(), o, e);
  out = o.str();
  err = e.str();
  return code;
}

}  // namespace

TEST_CASE("image lists: malformed lines are reported as file:line", "[frontend][dataset]") {
  ScratchDir dir("lists");
  SECTION("a line with three fields") {
    const auto path = dir.write("rgb.txt", std::string(kListHeader) +
                                               "1.0 rgb/1.png\n"
                                               "2.0 rgb/2.png extra\n");
    REQUIRE_THROWS_WITH(hbos::slam::read_image_list(path),
                        Contains(path + ":4") && Contains("expected 'timestamp filename'"));
  }
  SECTION("a stamp that is not a number") {
    const auto path =
        dir.write("rgb.txt", std::string(kListHeader) + "1.0 rgb/1.png\n1.x rgb/2.png\n");
    REQUIRE_THROWS_WITH(hbos::slam::read_image_list(path),
                        Contains(path + ":4") && Contains("\"1.x\" is not a finite number"));
  }
  SECTION("a stamp that does not increase") {
    const auto path = dir.write("rgb.txt", std::string(kListHeader) + "2.0 a.png\n\n2.0 b.png\n");
    REQUIRE_THROWS_WITH(hbos::slam::read_image_list(path),
                        Contains(path + ":5") && Contains("does not increase (line 3"));
  }
  SECTION("a line without a file name") {
    const auto path = dir.write("rgb.txt", "1.0\n");
    REQUIRE_THROWS_WITH(hbos::slam::read_image_list(path), Contains(path + ":1"));
  }
  SECTION("no image at all") {
    const auto path = dir.write("rgb.txt", kListHeader);
    REQUIRE_THROWS_WITH(hbos::slam::read_image_list(path), Contains("lists no image"));
  }
  SECTION("comments, blank lines and CRLF are accepted") {
    const auto path =
        dir.write("rgb.txt", std::string(kListHeader) + "\n1.5 rgb/1.png\r\n  \n2.5 rgb/2.png\n");
    const auto images = hbos::slam::read_image_list(path);
    REQUIRE(images.size() == 2);
    CHECK(images[0].stamp == 1.5);
    CHECK(images[0].path == "rgb/1.png");
    CHECK(images[0].line == 4);
    CHECK(images[1].line == 6);
  }
}

TEST_CASE("sequences: missing pieces are named", "[frontend][dataset]") {
  ScratchDir dir("sequence");
  SECTION("missing folder") {
    REQUIRE_THROWS_WITH(hbos::slam::load_tum_sequence(dir.file("nowhere")),
                        Contains("nowhere") && Contains("does not exist"));
  }
  SECTION("missing depth.txt") {
    dir.write("rgb.txt", "1.0 rgb/1.png\n");
    REQUIRE_THROWS_WITH(hbos::slam::load_tum_sequence(dir.path().string()),
                        Contains("cannot open image list") && Contains("depth.txt"));
  }
  SECTION("no colour image has a depth image within the limit") {
    dir.write("rgb.txt", "1.00 rgb/1.png\n");
    dir.write("depth.txt", "1.05 depth/1.png\n");
    REQUIRE_THROWS_WITH(hbos::slam::load_tum_sequence(dir.path().string()),
                        Contains("no colour image has a depth image within 0.02 s"));
  }
  SECTION("an unreadable image names the list line") {
    dir.write("rgb.txt", "# header\n1.00 rgb/1.png\n");
    dir.write("depth.txt", "1.01 depth/1.png\n");
    const auto sequence = hbos::slam::load_tum_sequence(dir.path().string());
    REQUIRE(sequence.size() == 1);
    CHECK_FALSE(sequence.groundtruth.has_value());
    REQUIRE_THROWS_WITH(hbos::slam::read_frame_images(sequence, 0, 5000.0),
                        Contains("rgb/1.png") && Contains("rgb.txt:2"));
  }
}

TEST_CASE("sequences: colour images take the nearest depth image", "[frontend][dataset]") {
  ScratchDir dir("nearest");
  // Depth runs 15 ms ahead of colour; the colour image at 2.000 has depth at 1.985 (15 ms) and
  // 2.018 (18 ms): the nearest, 1.985, must be taken. 3.000 has none within 20 ms.
  dir.write("rgb.txt", "1.000 rgb/1.png\n2.000 rgb/2.png\n3.000 rgb/3.png\n");
  dir.write("depth.txt", "0.985 d/0.png\n1.985 d/1.png\n2.018 d/2.png\n2.975 d/3.png\n");
  const auto sequence = hbos::slam::load_tum_sequence(dir.path().string());
  REQUIRE(sequence.size() == 2);
  CHECK(sequence.frames[0].depth.path == "d/0.png");
  CHECK(sequence.frames[1].depth.path == "d/1.png");
  CHECK(sequence.unpaired_rgb == 1);
}

TEST_CASE("the embedded fr1/xyz sequence loads with ground truth", "[frontend][dataset]") {
  const auto sequence = hbos::slam::load_tum_sequence(slam_data("fr1_xyz_37").string());
  REQUIRE(sequence.size() == 37);
  REQUIRE(sequence.groundtruth.has_value());
  // The ground truth covers every frame (trimmed to the frames' span +- 1 s).
  CHECK(sequence.groundtruth->stamps.front() < sequence.frames.front().rgb.stamp - 0.9);
  CHECK(sequence.groundtruth->stamps.back() > sequence.frames.back().rgb.stamp + 0.9);
  for (const auto& f : sequence.frames) CHECK(std::abs(f.rgb.stamp - f.depth.stamp) < 0.02);
  const auto images = hbos::slam::read_frame_images(sequence, 0, 5000.0);
  CHECK(images.bgr.type() == CV_8UC3);
  CHECK(images.depth_m.type() == CV_32FC1);
  CHECK(images.bgr.size() == cv::Size(640, 480));
  // A desk scene seen from ~1 m: the median measured depth lies between 0.5 and 3 m.
  std::vector<float> valid;
  for (int y = 0; y < images.depth_m.rows; y += 8) {
    for (int x = 0; x < images.depth_m.cols; x += 8) {
      if (images.depth_m.at<float>(y, x) > 0.f) valid.push_back(images.depth_m.at<float>(y, x));
    }
  }
  REQUIRE(valid.size() > 1000);
  std::nth_element(valid.begin(), valid.begin() + static_cast<std::ptrdiff_t>(valid.size() / 2),
                   valid.end());
  CHECK(valid[valid.size() / 2] > 0.5f);
  CHECK(valid[valid.size() / 2] < 3.0f);
}

TEST_CASE("cameras: presets, ORB-SLAM2 YAML, JSON and their errors", "[frontend][camera]") {
  const auto tum1 = hbos::slam::camera_preset("tum1");
  CHECK(tum1.fx == 517.306408);
  CHECK(tum1.k3 == 1.163314);
  CHECK(tum1.has_distortion());
  const auto tum3 = hbos::slam::load_camera("tum3");
  CHECK(tum3.fx == 535.4);
  CHECK_FALSE(tum3.has_distortion());
  CHECK_THROWS_WITH(hbos::slam::load_camera("tum9"), Contains("'tum9' is not one of tum1, tum3"));

  ScratchDir dir("camera");
  SECTION("an ORB-SLAM2 settings file loads as is") {
    const auto path =
        dir.write("TUM1.yaml",
                  "%YAML:1.0\n# Camera Parameters\nCamera.fx: 517.306408\n"
                  "Camera.fy: 516.469215\nCamera.cx: 318.643040\nCamera.cy: 255.313989\n"
                  "Camera.k1: 0.262383\nCamera.k2: -0.953104\nCamera.p1: -0.005358\n"
                  "Camera.p2: 0.002628\nCamera.k3: 1.163314\nCamera.fps: 30.0\n"
                  "DepthMapFactor: 5000.0\nORBextractor.nFeatures: 1000\n");
    const auto c = hbos::slam::load_camera(path);
    CHECK(c.fx == tum1.fx);
    CHECK(c.p2 == tum1.p2);
    CHECK(c.depth_factor == 5000.0);
  }
  SECTION("JSON") {
    const auto path = dir.write(
        "cam.json", R"({"fx": 500, "fy": 501, "cx": 320, "cy": 240, "depth_factor": 1000})");
    const auto c = hbos::slam::load_camera(path);
    CHECK(c.fy == 501.0);
    CHECK(c.depth_factor == 1000.0);
    CHECK_FALSE(c.has_distortion());
  }
  SECTION("a YAML value that is not a number names file:line and field") {
    const auto path = dir.write("bad.yaml", "fx: 500\nfy: five hundred\n");
    CHECK_THROWS_WITH(hbos::slam::load_camera(path),
                      Contains(path + ":2") && Contains("'fy' is not a number"));
  }
  SECTION("a missing required field is named") {
    const auto path = dir.write("partial.yml", "fx: 500\nfy: 500\ncx: 320\n");
    CHECK_THROWS_WITH(hbos::slam::load_camera(path), Contains("missing field 'cy'"));
  }
  SECTION("a non-positive focal length is refused") {
    const auto path = dir.write("neg.json", R"({"fx": -1, "fy": 500, "cx": 320, "cy": 240})");
    CHECK_THROWS_WITH(hbos::slam::load_camera(path), Contains("is not a plausible focal length"));
  }
  SECTION("broken JSON names the line") {
    const auto path = dir.write("broken.json", "{\n\"fx\": 500,\n\"fy\": }\n");
    CHECK_THROWS_WITH(hbos::slam::load_camera(path), Contains(path + ":3"));
  }
}

TEST_CASE("undistortion inverts the fr1 distortion and leaves tum3 alone", "[frontend][camera]") {
  const auto tum1 = hbos::slam::camera_preset("tum1");
  const std::vector<cv::Point2f> pixels = {{318.643f, 255.314f}, {10.f, 10.f}, {600.f, 400.f}};
  const auto undistorted = hbos::slam::undistort_pixels(tum1, pixels);
  CHECK(cv::norm(undistorted[0] - pixels[0]) < 1e-2);
  // fr1's k1 > 0 pushes image corners outwards; undistorted, they move towards the centre.
  CHECK(undistorted[1].x > pixels[1].x + 1.f);
  CHECK(undistorted[1].y > pixels[1].y + 1.f);
  // Distorting the undistorted pixels again (OpenCV's forward model) gives the originals back.
  std::vector<cv::Point3f> rays;
  for (const auto& u : undistorted) {
    rays.emplace_back(static_cast<float>((u.x - tum1.cx) / tum1.fx),
                      static_cast<float>((u.y - tum1.cy) / tum1.fy), 1.f);
  }
  std::vector<cv::Point2f> redistorted;
  cv::projectPoints(rays, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), tum1.camera_matrix(),
                    tum1.distortion_coefficients(), redistorted);
  for (std::size_t i = 0; i < pixels.size(); ++i)
    CHECK(cv::norm(redistorted[i] - pixels[i]) < 0.05);
  const auto same = hbos::slam::undistort_pixels(hbos::slam::camera_preset("tum3"), pixels);
  CHECK(same[1] == pixels[1]);
}

TEST_CASE("hbos-slam: bad input exits with 2 and says what is wrong", "[frontend][command]") {
  std::string out, err;
  SECTION("unknown screen") {
    CHECK(run_command({"--screen", "magic"}, out, err) == 2);
    CHECK_THAT(err, Contains("--screen") && Contains("magic"));
  }
  SECTION("missing dataset folder") {
    CHECK(run_command({"--dataset", "/nonexistent/fr1", "--quiet"}, out, err) == 2);
    CHECK_THAT(err, Contains("hbos-slam: error:") && Contains("/nonexistent/fr1"));
  }
  SECTION("malformed camera file") {
    ScratchDir dir("command");
    const auto camera = dir.write("cam.yaml", "fx: 500\nfy 500\n");
    CHECK(run_command({"--camera", camera, "--quiet"}, out, err) == 2);
    CHECK_THAT(err, Contains(camera + ":2"));
  }
  SECTION("figure frame beyond the frames run") {
    ScratchDir dir("figure");
    CHECK(run_command({"--frames", "3", "--figure-frame", "5", "--quiet", "--out", dir.file("out")},
                      out, err) == 2);
    CHECK_THAT(err, Contains("--figure-frame 5"));
  }
}
