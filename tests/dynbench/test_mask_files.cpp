// Masks from files (hbos-slam --mask-dir): matched to frames by file name or stamp, checked
// before the run (a missing or wrongly sized mask names the file), both conventions; and the
// ground-truth labels read from an objects/ folder.

#include <catch2/catch.hpp>

#include "frontend/frame_source.hpp"
#include "frontend/mask_files.hpp"
#include "frontend/slam_command.hpp"
#include "test_frontend_support.hpp"
#include "tum_folder.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>
#include <nlohmann/json.hpp>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using hbos_test::ScratchDir;
namespace fs = std::filesystem;

namespace {

int slam(const std::vector<std::string>& args, std::string* out_text = nullptr,
         std::string* err_text = nullptr) {
  std::vector<const char*> argv = {"hbos-slam"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  const int rc = hbos::slam::run_slam_command(static_cast<int>(argv.size()), argv.data(), out, err);
  if (out_text != nullptr) *out_text = out.str();
  if (err_text != nullptr) *err_text = err.str();
  return rc;
}

cv::Mat read_gray(const fs::path& p) { return cv::imread(p.string(), cv::IMREAD_UNCHANGED); }

long count_nonzero(const cv::Mat& m) { return static_cast<long>(cv::countNonZero(m)); }

}  // namespace

TEST_CASE("mask files: matched by file name, DynaSLAM convention gives the person",
          "[dynbench][mask_files]") {
  ScratchDir scratch("maskfiles_name");
  hbos_test::write_tum_folder(scratch.path().string(), 4);
  const auto sequence = hbos::slam::load_tum_sequence(scratch.path().string());
  const hbos::slam::MaskFiles masks(sequence, scratch.file("masks/perfect"),
                                    hbos::slam::MaskConvention::kDynaSlam, 0.02);
  for (int i = 0; i < 4; ++i) {
    const std::string stem = hbos_test::frame_stem(scratch.path().string(), i);
    CHECK(fs::path(masks.path(i)).stem().string() == stem);
    const cv::Mat mask = masks.mask(i);
    const cv::Mat ids = read_gray(scratch.path() / "objects" / (stem + ".png"));
    REQUIRE(mask.type() == CV_8UC1);
    // 255 exactly where the object ids say "person"; the person covers thousands of pixels.
    CHECK(count_nonzero(mask) > 1000);
    CHECK(cv::countNonZero(mask != (ids * 255)) == 0);
  }
}

TEST_CASE("mask files: nonzero-dynamic convention is the inverse", "[dynbench][mask_files]") {
  ScratchDir scratch("maskfiles_convention");
  hbos_test::write_tum_folder(scratch.path().string(), 2);
  const auto sequence = hbos::slam::load_tum_sequence(scratch.path().string());
  const hbos::slam::MaskFiles dyna(sequence, scratch.file("masks/perfect"),
                                   hbos::slam::MaskConvention::kDynaSlam, 0.02);
  const hbos::slam::MaskFiles nonzero(sequence, scratch.file("masks/perfect"),
                                      hbos::slam::MaskConvention::kNonzeroDynamic, 0.02);
  const cv::Mat a = dyna.mask(1), b = nonzero.mask(1);
  CHECK(count_nonzero(a) + count_nonzero(b) == static_cast<long>(a.total()));
  CHECK(cv::countNonZero(a & b) == 0);
  CHECK(hbos::slam::parse_mask_convention("nonzero-dynamic") ==
        hbos::slam::MaskConvention::kNonzeroDynamic);
  CHECK_THROWS_WITH(hbos::slam::parse_mask_convention("zero"),
                    Catch::Contains("'zero'") && Catch::Contains("dynaslam"));
}

TEST_CASE("mask files: matched by the nearest stamp within the tolerance",
          "[dynbench][mask_files]") {
  ScratchDir scratch("maskfiles_stamp");
  hbos_test::write_tum_folder(scratch.path().string(), 3);
  const auto sequence = hbos::slam::load_tum_sequence(scratch.path().string());
  // Masks named by a stamp 5 ms later than their frame's, as a segmenter's own clock might.
  const fs::path shifted = scratch.path() / "shifted";
  fs::create_directories(shifted);
  for (int i = 0; i < 3; ++i) {
    const std::string stem = hbos_test::frame_stem(scratch.path().string(), i);
    const double stamp = sequence.frames[static_cast<std::size_t>(i)].rgb.stamp + 0.005;
    fs::copy_file(scratch.path() / "masks" / "perfect" / (stem + ".png"),
                  shifted / fmt::format("{:.6f}.png", stamp));
  }
  const hbos::slam::MaskFiles masks(sequence, shifted.string(),
                                    hbos::slam::MaskConvention::kDynaSlam, 0.02);
  for (int i = 0; i < 3; ++i) {
    const double stamp = sequence.frames[static_cast<std::size_t>(i)].rgb.stamp + 0.005;
    CHECK(fs::path(masks.path(i)).filename().string() == fmt::format("{:.6f}.png", stamp));
  }
  // A tolerance below the 5 ms offset finds none.
  CHECK_THROWS_WITH(hbos::slam::MaskFiles(sequence, shifted.string(),
                                          hbos::slam::MaskConvention::kDynaSlam, 0.004),
                    Catch::Contains("no mask for frame 0") && Catch::Contains("within 0.004 s"));
}

TEST_CASE("mask files: a missing or wrongly sized mask stops before the run, naming the file",
          "[dynbench][mask_files]") {
  ScratchDir scratch("maskfiles_errors");
  hbos_test::write_tum_folder(scratch.path().string(), 4);
  const std::string root = scratch.path().string();
  const auto sequence = hbos::slam::load_tum_sequence(root);
  const std::string stem2 = hbos_test::frame_stem(root, 2);
  const fs::path masks = scratch.path() / "masks" / "perfect";

  SECTION("missing") {
    fs::remove(masks / (stem2 + ".png"));
    hbos::slam::MaskConfig config;
    config.source = hbos::slam::MaskSource::kFiles;
    config.files_dir = masks.string();
    // The FrameSource (built before the first frame is tracked) already refuses.
    CHECK_THROWS_AS(hbos::slam::FrameSource(sequence, 5000.0, {}, config), hbos::InvalidArgument);
    CHECK_THROWS_WITH(hbos::slam::FrameSource(sequence, 5000.0, {}, config),
                      Catch::Contains("no mask for frame 2") && Catch::Contains(stem2) &&
                          Catch::Contains("rgb.txt:4"));
    std::string err;
    CHECK(slam({"--dataset", root, "--camera", "tum1", "--mask-dir", masks.string(), "--quiet",
                "--out", scratch.file("out")},
               nullptr, &err) == hbos::slam::kSlamBadInput);
    CHECK_THAT(err, Catch::Contains("no mask for frame 2"));
    CHECK_FALSE(fs::exists(scratch.path() / "out" / "trajectory.txt"));
  }
  SECTION("wrong size") {
    const cv::Mat small(240, 320, CV_8UC1, cv::Scalar(255));
    cv::imwrite((masks / (stem2 + ".png")).string(), small);
    CHECK_THROWS_WITH(hbos::slam::MaskFiles(sequence, masks.string(),
                                            hbos::slam::MaskConvention::kDynaSlam, 0.02),
                      Catch::Contains(stem2 + ".png") && Catch::Contains("is 320x240") &&
                          Catch::Contains("expected 640x480"));
    std::string err;
    CHECK(slam({"--dataset", root, "--camera", "tum1", "--mask-dir", masks.string(), "--quiet",
                "--out", scratch.file("out")},
               nullptr, &err) == hbos::slam::kSlamBadInput);
    CHECK_THAT(err, Catch::Contains("320x240"));
  }
  SECTION("not a folder, or no image in it") {
    CHECK_THROWS_WITH(hbos::slam::MaskFiles(sequence, scratch.file("nowhere"),
                                            hbos::slam::MaskConvention::kDynaSlam, 0.02),
                      Catch::Contains("nowhere") && Catch::Contains("does not exist"));
    fs::create_directories(scratch.path() / "empty");
    CHECK_THROWS_WITH(hbos::slam::MaskFiles(sequence, scratch.file("empty"),
                                            hbos::slam::MaskConvention::kDynaSlam, 0.02),
                      Catch::Contains("has no image"));
  }
  SECTION("options that contradict each other") {
    std::string err;
    CHECK(slam({"--dataset", root, "--mask", "exact", "--mask-dir", masks.string()}, nullptr,
               &err) == hbos::slam::kSlamBadInput);
    CHECK_THAT(err, Catch::Contains("--mask-dir needs --mask files"));
    CHECK(slam({"--dataset", root, "--mask", "files"}, nullptr, &err) == hbos::slam::kSlamBadInput);
    CHECK_THAT(err, Catch::Contains("needs --mask-dir"));
    CHECK(slam({"--dataset", root, "--mask-dir", masks.string(), "--mask-convention", "zero"},
               nullptr, &err) == hbos::slam::kSlamBadInput);
  }
}

TEST_CASE("hbos-slam --mask-dir: the masks are used and objects/ labels the matches",
          "[dynbench][mask_files]") {
  ScratchDir scratch("maskfiles_run");
  hbos_test::write_tum_folder(scratch.path().string(), 6);
  const std::string root = scratch.path().string();
  const auto summary = [&](const std::string& out) {
    std::ifstream in(fs::path(out) / "summary.json");
    return nlohmann::json::parse(in);
  };
  // No mask: the objects/ folder labels the person's matches (no composited person here).
  REQUIRE(slam({"--dataset", root, "--camera", "tum1", "--scenario", "static", "--mask", "none",
                "--quiet", "--out", scratch.file("none")}) == hbos::slam::kSlamOk);
  const auto unmasked = summary(scratch.file("none"));
  CHECK(unmasked["person_matches"].get<long>() > 50);
  // The perfect mask from files: no feature on the person, so no person match at all.
  std::string out;
  REQUIRE(slam({"--dataset", root, "--camera", "tum1", "--mask-dir", scratch.file("masks/perfect"),
                "--quiet", "--out", scratch.file("masked")},
               &out) == hbos::slam::kSlamOk);
  const auto masked = summary(scratch.file("masked"));
  CHECK(masked["settings"]["mask"] == "files");
  CHECK(masked["settings"]["scenario"] == "static");  // --mask-dir: nothing composited
  CHECK(masked["person_matches"].get<long>() == 0);
  // The inverted convention masks everything but the person: features only there.
  REQUIRE(slam({"--dataset", root, "--camera", "tum1", "--mask-dir", scratch.file("masks/perfect"),
                "--mask-convention", "nonzero-dynamic", "--quiet", "--out", scratch.file("inv")}) ==
          hbos::slam::kSlamOk);
  const auto inverted = summary(scratch.file("inv"));
  CHECK(inverted["matches"].get<long>() > 0);
  CHECK(inverted["person_matches"].get<double>() >= 0.9 * inverted["matches"].get<double>());
}
