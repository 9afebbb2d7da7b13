// Reading and writing TUM trajectory files: accepted syntax, every rejected case with its
// file:line message, the TUM-script-compatible duplicate handling, and bit-exact round trips.
#include "eval/trajectory_io.hpp"
#include "eval_test_support.hpp"

#include <catch2/catch.hpp>
#include <hbos/error.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

using Catch::Matchers::Contains;
using hbos::slam::parse_tum_trajectory;
using hbos::slam::ReadOptions;
using hbos::slam::ReadReport;
using hbos::slam::StampPolicy;
using hbos::slam::Trajectory;

namespace {

Trajectory parse(const std::string& text, const ReadOptions& options = {},
                 ReadReport* report = nullptr) {
  std::istringstream in(text);
  return parse_tum_trajectory(in, "est.txt", options, report);
}

ReadOptions lenient() {
  ReadOptions options;
  options.stamps = StampPolicy::kLikeTumScripts;
  return options;
}

}  // namespace

TEST_CASE("TUM reader accepts comments, blank lines, commas, tabs, CRLF and signs", "[eval][io]") {
  const std::string text =
      "# timestamp tx ty tz qx qy qz qw\n"
      "\n"
      "1.0 0 0 0 0 0 0 1\r\n"
      "2.0,1.5,-2,+3,0,0,0,1\n"
      "   \t \n"
      "  # an indented comment\n"
      "3.25\t1\t2\t3\t0\t0\t0.7071068\t0.7071068\n";
  ReadReport report;
  const Trajectory t = parse(text, {}, &report);
  REQUIRE(t.size() == 3);
  CHECK(t.name == "est.txt");
  CHECK(t.stamps == std::vector<double>{1.0, 2.0, 3.25});
  CHECK(t.positions.col(1) == Eigen::Vector3d(1.5, -2.0, 3.0));
  CHECK(t.quaternions.col(2) == Eigen::Vector4d(0.0, 0.0, 0.7071068, 0.7071068));
  CHECK(report.poses == 3);
  CHECK(report.data_lines == 3);
  CHECK(report.comment_lines == 2);
  CHECK(report.blank_lines == 2);
  CHECK(report.duplicates_dropped == 0);
  CHECK(report.warnings.empty());
}

TEST_CASE("TUM reader rejects malformed lines naming file:line, field and value", "[eval][io]") {
  const std::string good = "1.0 0 0 0 0 0 0 1\n";
  CHECK_THROWS_AS(parse(good + "2.0 0 0 0 0 0 1\n"), hbos::InvalidArgument);
  CHECK_THROWS_WITH(parse(good + "2.0 0 0 0 0 0 1\n"),
                    Contains("est.txt:2: expected 8 fields") && Contains("found 7"));
  CHECK_THROWS_WITH(parse(good + "2.0 0 0 0 0 0 0 1 9\n"),
                    Contains("est.txt:2") && Contains("found 9"));
  CHECK_THROWS_WITH(parse(good + "2.0\n"), Contains("est.txt:2") && Contains("found 1"));
  CHECK_THROWS_WITH(parse("\n\n1.0 0 0 0 abc 0 0 1\n"),
                    Contains("est.txt:3: field 'qx' is not a number: 'abc'"));
  CHECK_THROWS_WITH(parse("1.0x 0 0 0 0 0 0 1\n"),
                    Contains("est.txt:1: field 't' is not a number: '1.0x'"));
  CHECK_THROWS_WITH(parse("1.0 0 0 +-1 0 0 0 1\n"), Contains("field 'tz' is not a number: '+-1'"));
  // A byte order mark is shown, not printed invisibly before a stamp that looks right.
  CHECK_THROWS_WITH(parse("\xEF\xBB\xBF"
                          "1.0 0 0 0 0 0 0 1\n"),
                    Contains("field 't' is not a number: '\\xef\\xbb\\xbf1.0'"));
  // A 10 MB field makes a message of a line, not of 10 MB.
  const std::string huge(10'000'000, '7');
  try {
    static_cast<void>(parse(huge + "x 0 0 0 0 0 0 1\n"));
    FAIL("accepted");
  } catch (const hbos::InvalidArgument& e) {
    CHECK(std::string(e.what()).size() < 200);
    CHECK_THAT(e.what(), Contains("7777...'"));
  }
  CHECK_THROWS_WITH(parse("1.0 0 0 nan 0 0 0 1\n"),
                    Contains("est.txt:1: field 'tz' is not finite: 'nan'"));
  CHECK_THROWS_WITH(parse(good + "2.0 inf 0 0 0 0 0 1\n"),
                    Contains("est.txt:2: field 'tx' is not finite: 'inf'"));
  CHECK_THROWS_WITH(parse("1.0 0 0 0 0 0 0 1e999\n"),
                    Contains("field 'qw' is not finite: '1e999'"));
}

TEST_CASE("TUM reader rejects quaternions far from unit length", "[eval][io]") {
  CHECK_THROWS_WITH(parse("1.0 0 0 0 0 0 0 0.5\n"),
                    Contains("est.txt:1: quaternion (qx qy qz qw) = (0 0 0 0.5) has norm 0.5"));
  // All-zero quaternions (which evaluate_rpe.py skips silently) are rejected too.
  CHECK_THROWS_WITH(parse("1.0 0 0 0 0 0 0 0\n"), Contains("has norm 0"));
  // Rounding to 4 decimals, as in TUM ground truth, is well inside the default tolerance.
  CHECK(parse("1.0 1.3563 0.6305 1.6380 0.6132 0.5962 -0.3311 -0.3986\n").size() == 1);
  ReadOptions tight;
  tight.max_quaternion_norm_error = 1e-6;
  CHECK_THROWS_WITH(parse("1.0 1.3563 0.6305 1.6380 0.6132 0.5962 -0.3311 -0.3986\n", tight),
                    Contains("farther than 1e-06 from 1"));
  ReadOptions invalid;
  invalid.max_quaternion_norm_error = -1.0;
  CHECK_THROWS_WITH(parse("1.0 0 0 0 0 0 0 1\n", invalid), Contains("max_quaternion_norm_error"));
}

TEST_CASE("TUM reader, strict: repeated or decreasing stamps are errors", "[eval][io]") {
  const std::string text = "1.0 0 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n";
  CHECK_THROWS_WITH(
      parse(text + "2.0 2 0 0 0 0 0 1\n"),
      Contains("est.txt:3: stamp 2.0 repeats line 2") && Contains("--lenient-duplicates"));
  CHECK_THROWS_WITH(parse(text + "1.5 2 0 0 0 0 0 1\n"),
                    Contains("est.txt:3: stamp 1.5 is earlier than 2.0 on line 2"));
  // "2" and "2.000" are the same stamp, as for the scripts' float keys.
  CHECK_THROWS_WITH(parse(text + "2.000 2 0 0 0 0 0 1\n"), Contains("repeats line 2"));
  CHECK_THROWS_WITH(parse("# only a comment\n\n"), Contains("est.txt: no poses found"));
  CHECK_THROWS_WITH(hbos::slam::read_tum_trajectory(hbos::slam::test::eval_data("missing.txt")),
                    Contains("missing.txt: a trajectory file does not exist"));
}

TEST_CASE("TUM reader, like the scripts: sort, and a repeated stamp keeps the last line",
          "[eval][io]") {
  const std::string text =
      "2.0 2 0 0 0 0 0 1\n"
      "1.0 1 0 0 0 0 0 1\n"
      "2.0 3 0 0 0 0 0 1\n"
      "3.0 4 0 0 0 0 0 1\n"
      "2.0 5 0 0 0 0 0 1\n";
  ReadReport report;
  const Trajectory t = parse(text, lenient(), &report);
  REQUIRE(t.size() == 3);
  CHECK(t.stamps == std::vector<double>{1.0, 2.0, 3.0});
  CHECK(t.positions(0, 1) == 5.0);  // line 5, the last of the three lines with stamp 2.0
  CHECK(report.data_lines == 5);
  CHECK(report.duplicates_dropped == 2);
  CHECK(report.reordered);
  REQUIRE(report.warnings.size() == 3);
  CHECK_THAT(report.warnings[1], Contains("est.txt:1: stamp 2.0 repeats at line 3"));
  CHECK_THAT(report.warnings[2], Contains("est.txt:3: stamp 2.0 repeats at line 5"));
}

TEST_CASE("TUM reader on fr2/desk's duplicated ground-truth stamp", "[eval][io]") {
  const std::string path =
      hbos::slam::test::eval_data("data/tum_trajectories_evo/fr2_desk_groundtruth_excerpt.txt");
  CHECK_THROWS_WITH(hbos::slam::read_tum_trajectory(path),
                    Contains("fr2_desk_groundtruth_excerpt.txt:10: stamp 1311868229.5760 repeats "
                             "line 9"));
  ReadReport report;
  const Trajectory t = hbos::slam::read_tum_trajectory(path, lenient(), &report);
  CHECK(report.data_lines == 16);
  CHECK(t.size() == 15);
  CHECK(report.duplicates_dropped == 1);
  CHECK_FALSE(report.reordered);
  // The dict of the TUM scripts holds the second of the two lines.
  const auto it = std::find(t.stamps.begin(), t.stamps.end(), 1311868229.5760);
  REQUIRE(it != t.stamps.end());
  const auto i = static_cast<Eigen::Index>(it - t.stamps.begin());
  CHECK(t.positions.col(i) == Eigen::Vector3d(1.4044, 0.9614, 1.3683));
  CHECK(t.quaternions.col(i) == Eigen::Vector4d(-0.0177, 0.8973, -0.4353, 0.0703));
}

TEST_CASE("write_tum_trajectory round-trips every double exactly, atomically", "[eval][io]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1e3, 1e3);
  std::vector<double> stamps;
  std::vector<Eigen::Isometry3d> poses;
  double t = 1305031102.160407;
  for (int i = 0; i < 200; ++i) {
    t += 0.001 + std::abs(uniform(rng)) * 1e-4;
    stamps.push_back(t);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = hbos::slam::test::random_rotation(rng);
    // Up to 1e9 m: the reader refuses positions beyond (issue 11); every double in range
    // round-trips.
    pose.translation() << uniform(rng), uniform(rng) * 1e-9, uniform(rng) * 1e5;
    poses.push_back(pose);
  }
  const Trajectory original = hbos::slam::make_trajectory("random", stamps, poses);
  hbos::slam::test::ScratchDir dir;
  const std::string path = dir.file("out.txt");
  hbos::slam::write_tum_trajectory(path, original);
  const Trajectory back = hbos::slam::read_tum_trajectory(path);
  CHECK(back.stamps == original.stamps);
  CHECK(back.positions == original.positions);
  CHECK(back.quaternions == original.quaternions);
  // Only the result is left in the directory: the temporary file was renamed.
  CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                      std::filesystem::directory_iterator()) == 1);
}

TEST_CASE("rotation_from_quaternion normalises like transform44", "[eval][io]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> norm(0.01, 100.0);
  for (int k = 0; k < 100; ++k) {
    const Eigen::Quaterniond unit(hbos::slam::test::random_rotation(rng));
    const double s = norm(rng);
    const Eigen::Matrix3d r = hbos::slam::rotation_from_quaternion(s * unit.x(), s * unit.y(),
                                                                   s * unit.z(), s * unit.w());
    CHECK((r - unit.toRotationMatrix()).cwiseAbs().maxCoeff() < 1e-15);
  }
  CHECK_THROWS_WITH(hbos::slam::rotation_from_quaternion(0, 0, 0, 0), Contains("non-zero"));
}

TEST_CASE("read_frame_stamps reads the first column of rgb.txt", "[eval][io]") {
  hbos::slam::test::ScratchDir dir;
  {
    std::ofstream out(dir.file("rgb.txt"));
    out << "# color images\n# timestamp filename\n1305031102.175304 rgb/1305031102.175304.png\n"
           "1305031102.211214 rgb/1305031102.211214.png\n1305031102.143 rgb/x.png\n";
  }
  CHECK(hbos::slam::read_frame_stamps(dir.file("rgb.txt")) ==
        std::vector<double>{1305031102.143, 1305031102.175304, 1305031102.211214});
  {
    std::ofstream out(dir.file("bad.txt"));
    out << "1.0 a.png\nrgb/2.png 2.0\n";
  }
  CHECK_THROWS_WITH(hbos::slam::read_frame_stamps(dir.file("bad.txt")),
                    Contains("bad.txt:2: frame stamp is not a finite number: 'rgb/2.png'"));
  // A frame listed twice would count twice in the share of frames tracked.
  {
    std::ofstream out(dir.file("twice.txt"));
    out << "# timestamp filename\n2.5 b.png\n1.0 a.png\n2.5 c.png\n";
  }
  CHECK_THROWS_WITH(
      hbos::slam::read_frame_stamps(dir.file("twice.txt")),
      Contains("twice.txt:4: frame stamp 2.500000 is listed again (first at line 2)"));
}
