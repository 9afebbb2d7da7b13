// A short scenario renders end to end into a TUM folder; written twice it is the same bytes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "render/textures.hpp"
#include "render/trajectory.hpp"
#include "render/writer.hpp"

using namespace hbos::render;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

std::vector<std::string> data_lines(const fs::path& p) {
  std::vector<std::string> out;
  std::istringstream in(slurp(p));
  for (std::string l; std::getline(in, l);) {
    if (!l.empty() && l[0] != '#') out.push_back(l);
  }
  return out;
}

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("hbos_render_test_" + name);
  fs::remove_all(p);
  return p;
}

// The walking_static scenario, `frames` long, with `seed`.
SequenceOptions walking_static(int frames, std::uint64_t seed) {
  SequenceOptions o;
  o.scenario = "walking_static";
  o.frames = frames;
  o.seed = seed;
  return o;
}

}  // namespace

TEST_CASE("a 30-frame scenario renders to a complete TUM folder") {
  SequenceRenderer r(walking_static(30, 5));
  const fs::path out = scratch("e2e");
  int calls = 0;
  const WriteStats s = write_sequence(r, out, false, [&](int, int) { ++calls; });
  CHECK(s.frames == 30);
  CHECK(calls == 30);
  CHECK_FALSE(fs::exists(out.string() + ".tmp"));
  const auto rgb = data_lines(out / "rgb.txt");
  const auto depth = data_lines(out / "depth.txt");
  const auto gt = data_lines(out / "groundtruth.txt");
  REQUIRE(rgb.size() == 30);
  REQUIRE(depth.size() == 30);
  REQUIRE(gt.size() == 30);
  CHECK(slurp(out / "groundtruth.txt").rfind("# ground truth trajectory\n", 0) == 0);
  // The first stamp is the ground truth's first, then 1/30 s apart.
  double prev = 0;
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    std::istringstream ls(rgb[i]);
    double stamp = 0;
    std::string file;
    ls >> stamp >> file;
    if (i == 0) CHECK(stamp == Approx(1341846226.9190).margin(1e-6));
    if (i > 0) CHECK(stamp - prev == Approx(1.0 / 30.0).margin(2e-6));
    prev = stamp;
    REQUIRE(fs::exists(out / file));
    const std::string name = fs::path(file).filename().string();
    const cv::Mat d = cv::imread((out / "depth" / name).string(), cv::IMREAD_UNCHANGED);
    REQUIRE(d.type() == CV_16U);
    REQUIRE(fs::exists(out / "objects" / name));
    for (const auto& v : mask_variant_names()) REQUIRE(fs::exists(out / "masks" / v / name));
    std::istringstream gs(gt[i]);
    double gstamp = 0, x = 0;
    gs >> gstamp;
    int fields = 0;
    while (gs >> x) ++fields;
    CHECK(fields == 7);
    CHECK(gstamp == stamp);
  }
  // Depth in range: some valid returns between 0.5 and 5 m (5000 units per metre), and holes.
  const cv::Mat d0 = cv::imread(
      (out / "depth" / (fs::path(rgb[0].substr(rgb[0].find(' ') + 1)).filename())).string(),
      cv::IMREAD_UNCHANGED);
  double lo = 0, hi = 0;
  cv::minMaxLoc(d0, &lo, &hi);
  CHECK(lo == 0.0);
  // The range cut is on the true depth; noise of up to 5 sigma(max range) may lie beyond it.
  const KinectModel km;
  const double sigma_max =
      km.sigma_a + km.sigma_b * (km.max_range - km.sigma_z0) * (km.max_range - km.sigma_z0);
  CHECK(hi <= (km.max_range + 5 * sigma_max) * km.depth_scale);
  CHECK(hi > 0.8 * km.max_range * km.depth_scale);
  CHECK(cv::countNonZero(d0) > static_cast<int>(d0.total() / 2));
  const auto j = nlohmann::json::parse(slurp(out / "scenario.json"));
  CHECK(j["scenario"] == "walking_static");
  CHECK(j["seed"] == 5);
  CHECK(j["frames"] == 30);
  CHECK(j["renderer_version"] == kRendererVersion);
  CHECK(j["people"].size() == 2);
  CHECK(j["objects"][0]["id"] == 3);
  // The folder exists now: a second write refuses, unless told to overwrite.
  CHECK_THROWS_AS(write_sequence(r, out, false), OutputError);
  fs::remove_all(out);
}

TEST_CASE("the same scenario and seed write the same bytes, file for file") {
  std::vector<fs::path> outs;
  for (int k = 0; k < 2; ++k) {
    SequenceOptions o;
    o.scenario = "sitting_xyz";
    o.frames = 6;
    o.seed = 9;
    SequenceRenderer r(o);
    outs.push_back(scratch("same" + std::to_string(k)));
    write_sequence(r, outs.back(), false);
  }
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(outs[0])) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), outs[0]);
    INFO(rel.string());
    REQUIRE(fs::exists(outs[1] / rel));
    CHECK(slurp(e.path()) == slurp(outs[1] / rel));
    ++files;
  }
  // 6 frames x (rgb, depth, objects, 8 masks) + 5 index files.
  CHECK(files == 6 * 11 + 5);
  for (const auto& p : outs) fs::remove_all(p);
}

TEST_CASE("overwriting replaces only a previous output, never other files or the current folder") {
  SequenceRenderer r(walking_static(2, 1));
  const fs::path dir = scratch("overwrite_guard");
  fs::create_directories(dir);
  // A folder of the user's own files: kept, whatever --overwrite says.
  const fs::path mine = dir / "mine";
  fs::create_directories(mine);
  std::ofstream(mine / "notes.txt") << "keep\n";
  CHECK_THROWS_WITH(write_sequence(r, mine, true),
                    Catch::Contains("holds files hbos-render did not write"));
  CHECK(slurp(mine / "notes.txt") == "keep\n");
  // A file: not replaced by a folder.
  const fs::path file = dir / "file.txt";
  std::ofstream(file) << "keep\n";
  CHECK_THROWS_WITH(write_sequence(r, file, true), Catch::Contains("not a folder"));
  CHECK(slurp(file) == "keep\n");
  // Paths that name no folder of their own.
  for (const fs::path& p : {fs::path(""), fs::path("."), fs::path(".."), fs::path("/")})
    CHECK_THROWS_WITH(write_sequence(r, p, true), Catch::Contains("names no folder of its own"));
  // A stale <out>.tmp holding other files is not deleted either.
  const fs::path out = dir / "seq";
  fs::create_directories(dir / "seq.tmp");
  std::ofstream(dir / "seq.tmp" / "notes.txt") << "keep\n";
  CHECK_THROWS_WITH(write_sequence(r, out, false), Catch::Contains("move it away"));
  CHECK(slurp(dir / "seq.tmp" / "notes.txt") == "keep\n");
  fs::remove_all(dir / "seq.tmp");
  // A previous output is replaced.
  write_sequence(r, out, false);
  const WriteStats again = write_sequence(r, out, true);
  CHECK(again.frames == 2);
  CHECK(fs::exists(out / "scenario.json"));
  fs::remove_all(dir);
}

TEST_CASE("a stop request between frames leaves no output and no temporary folder") {
  SequenceRenderer r(walking_static(5, 1));
  const fs::path out = scratch("interrupted");
  volatile std::sig_atomic_t stop = 0;
  // Ctrl-C arrives while the third frame is written.
  const auto progress = [&](int done, int) {
    if (done == 2) stop = 1;
  };
  CHECK_THROWS_WITH(write_sequence(r, out, false, progress, &stop),
                    Catch::Contains("interrupted after 2 of 5 frames"));
  CHECK_FALSE(fs::exists(out));
  CHECK_FALSE(fs::exists(out.string() + ".tmp"));
}

TEST_CASE("a repeated ground-truth stamp: the real file's near twin is kept, a far one refused") {
  const fs::path dir = scratch("repeated_stamp");
  fs::create_directories(dir);
  // The real fr3/walking_static ground truth repeats 1341846251.4587 with poses 0.5 mm apart.
  const auto real = read_tum_trajectory(default_data_dir() / "trajectories" /
                                        "fr3_walking_static_groundtruth.txt");
  CHECK(std::adjacent_find(real.begin(), real.end(), [](const auto& a, const auto& b) {
          return a.stamp == b.stamp;
        }) == real.end());
  const fs::path far = dir / "far.txt";
  std::ofstream(far)
      << "1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 0 1\n2.0 0.5 0 0 0 0 0 1\n3.0 0 0 0 0 0 0 1\n";
  CHECK_THROWS_WITH(read_tum_trajectory(far),
                    Catch::Contains("far.txt:3: timestamp 2.000000 repeats with a pose 50.0"));
  fs::remove_all(dir);
}

TEST_CASE(
    "textures are decoded from the bytes checked: imread's pixels, and a missing file named") {
  // The loader reads each file once and decodes those bytes: the murals are imread's images.
  const TextureLibrary library(default_data_dir());
  const cv::Mat hall3 =
      cv::imread((default_data_dir() / "textures" / "slambook2_ch11_3.jpg").string());
  REQUIRE(hall3.size() == library.get("wall_front").size());
  CHECK(cv::norm(hall3, library.get("wall_front"), cv::NORM_INF) == 0.0);

  const fs::path dir = scratch("missing_texture");
  fs::create_directories(dir / "textures");
  for (const auto& entry : fs::directory_iterator(default_data_dir() / "textures"))
    if (entry.path().filename() != "fr1_xyz_1305031102.175304.jpg")
      fs::copy_file(entry.path(), dir / "textures" / entry.path().filename());
  CHECK_THROWS_WITH(TextureLibrary(dir), Catch::Contains("cannot open texture image") &&
                                             Catch::Contains("fr1_xyz_1305031102.175304.jpg"));
  fs::remove_all(dir);
}

TEST_CASE("a truncated texture is refused, not rendered with libjpeg's grey rows") {
  const fs::path dir = scratch("truncated_texture");
  fs::create_directories(dir / "textures");
  for (const auto& entry : fs::directory_iterator(default_data_dir() / "textures"))
    fs::copy_file(entry.path(), dir / "textures" / entry.path().filename());
  const fs::path texture = dir / "textures" / "slambook2_ch11_3.jpg";
  const std::string bytes = slurp(texture);
  std::ofstream(texture, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2);
  CHECK_THROWS_WITH(TextureLibrary(dir),
                    Catch::Contains("slambook2_ch11_3.jpg is a truncated JPEG"));
  fs::remove_all(dir);
}
