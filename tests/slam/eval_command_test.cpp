// The hbos-eval command end to end (through run_eval_command, the executable's whole body):
// table, JSON, plots, exit codes and messages.
#include "eval/eval_command.hpp"
#include "eval_test_support.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

using Catch::Matchers::Contains;
using hbos::slam::test::eval_data;
using hbos::slam::test::ScratchDir;

namespace {

struct Run {
  int code = -1;
  std::string out;
  std::string err;
};

Run run(std::vector<std::string> args) {
  args.insert(args.begin(), "hbos-eval");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  std::ostringstream out;
  std::ostringstream err;
  Run r;
  r.code = hbos::slam::run_eval_command(static_cast<int>(argv.size()), argv.data(), out, err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

const std::string kGt = eval_data("data/tum_trajectories_evo/freiburg1_xyz-groundtruth.txt");
const std::string kRgbdslam = eval_data("data/tum_trajectories_evo/freiburg1_xyz-rgbdslam.txt");
const std::string kMono = eval_data("data/tum_trajectories_evo/freiburg1_xyz-ORB_kf_mono.txt");

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in);
  return nlohmann::json::parse(in);
}

}  // namespace

TEST_CASE("hbos-eval prints a labelled table and writes JSON and plots", "[eval][command]") {
  ScratchDir dir;
  const Run r = run({kGt, kRgbdslam, "--json", dir.file("result.json"), "--plot", dir.file("png")});
  INFO(r.err);
  REQUIRE(r.code == 0);
  // The TUM scripts' 6-decimal numbers, each row labelled.
  CHECK_THAT(r.out, Contains("RMSE                    0.013473      0.021217      0.934480"));
  CHECK_THAT(r.out, Contains("mean                    0.012029      0.019524      0.841472"));
  CHECK_THAT(r.out, Contains("std (population)"));
  CHECK_THAT(r.out, Contains("786 pairs"));
  CHECK_THAT(r.out, Contains("is the RMSE row"));
  CHECK_THAT(r.out, Contains("fixed delta 1 s"));
  CHECK(r.err.empty());

  const nlohmann::json j = read_json(dir.file("result.json"));
  CHECK(j.at("tool") == "hbos-eval");
  CHECK(j.at("ate").at("compared_pose_pairs") == 786);
  CHECK(j.at("ate").at("rmse").get<double>() == Approx(0.013473467769906794).epsilon(1e-9));
  CHECK(j.at("rpe").at("compared_pose_pairs") == 753);
  CHECK(j.at("rpe").at("trans_m").at("rmse").get<double>() ==
        Approx(0.0212174440791267).epsilon(1e-9));
  CHECK(j.at("rpe").at("rot_deg").at("mean").get<double>() ==
        Approx(0.8414723284399599).epsilon(1e-9));
  CHECK(j.at("inputs").at("groundtruth").at("poses") == 3000);
  CHECK(j.at("settings").at("stamp_policy") == "strict");
  CHECK_FALSE(j.contains("ate_sim3"));
  for (const char* png : {"top_view.png", "ate_over_time.png", "rpe_over_time.png"}) {
    CHECK(std::filesystem::file_size(dir.path() / "png" / png) > 10000);
  }
  // result.json and png/: the JSON's temporary file was renamed away.
  CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                      std::filesystem::directory_iterator()) == 2);
}

TEST_CASE("hbos-eval --sim3 for a monocular estimate", "[eval][command]") {
  ScratchDir dir;
  const Run r = run({kGt, kMono, "--sim3", "--no-rpe", "--json", dir.file("mono.json")});
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Contains("ATE Sim(3)"));
  CHECK_THAT(r.out, Contains("Sim(3) scale (est -> gt): 1.105622"));
  const nlohmann::json j = read_json(dir.file("mono.json"));
  CHECK(j.at("ate_sim3").at("scale").get<double>() == Approx(1.1056223637370342).epsilon(1e-9));
  CHECK(j.at("ate_sim3").at("rmse").get<double>() == Approx(0.009754581898685107).epsilon(1e-9));
  CHECK(j.at("ate").at("rmse").get<double>() == Approx(0.02430163227762101).epsilon(1e-9));
  CHECK_FALSE(j.contains("rpe"));
  CHECK(j.at("tracked").at("evaluated_poses") == 32);
}

TEST_CASE("hbos-eval RPE units and association options", "[eval][command]") {
  const Run frames = run({kGt, kRgbdslam, "--rpe-delta", "10", "--rpe-unit", "frames"});
  REQUIRE(frames.code == 0);
  CHECK_THAT(frames.out, Contains("fixed delta 10 frames"));
  const Run metres = run({kGt, kRgbdslam, "--rpe-delta", "0.2", "--rpe-unit", "m"});
  REQUIRE(metres.code == 0);
  CHECK_THAT(metres.out, Contains("0.2 m travelled along the ground truth"));
  // A tighter association finds fewer pairs.
  const Run tight = run({kGt, kRgbdslam, "--max-diff", "0.002", "--no-rpe"});
  REQUIRE(tight.code == 0);
  CHECK_THAT(tight.out, Contains("|dt| < 0.002 s"));
  CHECK_THAT(tight.out, !Contains("786 pairs"));
  // The share tracked counted against the sequence's own frame list.
  ScratchDir dir;
  {
    std::ofstream rgb(dir.file("rgb.txt"));
    rgb << "# color images\n" << std::fixed << std::setprecision(6);
    for (int i = 0; i < 800; ++i) {
      rgb << 1305031098.7 + 0.0375 * i << " rgb/" << i << ".png\n";
    }
  }
  const Run listed = run(
      {kGt, kRgbdslam, "--no-rpe", "--frames", dir.file("rgb.txt"), "--json", dir.file("t.json")});
  REQUIRE(listed.code == 0);
  CHECK_THAT(listed.out, Contains("786 evaluated poses / 800 frames (frame list)"));
  CHECK(read_json(dir.file("t.json")).at("tracked").at("basis") == "frame list");
  CHECK(run({kGt, kRgbdslam, "--frames", dir.file("none.txt")}).code == 2);
  // Shifting the estimate by a second breaks the association entirely: bad input.
  const Run shifted = run({kGt, kRgbdslam, "--offset", "100"});
  CHECK(shifted.code == 2);
  CHECK_THAT(shifted.err, Contains("only 0 associated pose pairs"));
}

TEST_CASE("hbos-eval: bad input gives exit 2 and a message naming file:line", "[eval][command]") {
  ScratchDir dir;
  {
    std::ofstream bad(dir.file("bad.txt"));
    bad << "# estimate\n1305031102.160407 1 2 3 0 0 0 1\n1305031102.194330 1 2 3 0 0 1\n";
  }
  const Run malformed = run({kGt, dir.file("bad.txt")});
  CHECK(malformed.code == 2);
  CHECK_THAT(malformed.err, Contains("bad.txt:3: expected 8 fields") && Contains("found 7"));
  CHECK(malformed.out.empty());

  const Run missing = run({kGt, dir.file("nope.txt")});
  CHECK(missing.code == 2);
  CHECK_THAT(missing.err, Contains("nope.txt: a trajectory file does not exist"));

  const std::string excerpt =
      eval_data("data/tum_trajectories_evo/fr2_desk_groundtruth_excerpt.txt");
  const Run strict = run({excerpt, excerpt, "--no-rpe"});
  CHECK(strict.code == 2);
  CHECK_THAT(strict.err, Contains("excerpt.txt:10: stamp 1311868229.5760 repeats line 9"));
  const Run lenient = run({excerpt, excerpt, "--no-rpe", "--lenient-duplicates"});
  CHECK(lenient.code == 0);
  CHECK_THAT(lenient.err, Contains("warning") && Contains("kept the last one"));
  CHECK_THAT(lenient.out, Contains("15 pairs"));

  CHECK(run({kGt}).code == 2);
  CHECK(run({kGt, kRgbdslam, "--bogus"}).code == 2);
  CHECK(run({kGt, kRgbdslam, "--rpe-unit", "rad"}).code == 2);
  CHECK(run({kGt, kRgbdslam, "--max-diff", "-1"}).code == 2);
  const Run help = run({"--help"});
  CHECK(help.code == 0);
  CHECK_THAT(help.out, Contains("--lenient-duplicates"));

  // --json naming an input would replace it; --json '' was the same as no --json at all.
  const std::string estimate = dir.file("est.txt");
  std::filesystem::copy_file(kRgbdslam, estimate);
  const auto read = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  };
  const std::string before = read(estimate);
  const Run onto_input = run({kGt, estimate, "--json", estimate});
  CHECK(onto_input.code == 2);
  CHECK_THAT(onto_input.err, Contains("is the input file") && Contains("est.txt"));
  CHECK(read(estimate) == before);
  const Run empty_json = run({kGt, kRgbdslam, "--json", ""});
  CHECK(empty_json.code == 2);
  CHECK_THAT(empty_json.err, Contains("an empty path names no file"));
}

TEST_CASE("hbos-eval: an output that cannot be written gives exit 1", "[eval][command]") {
  ScratchDir dir;
  const Run r = run({kGt, kRgbdslam, "--json", dir.file("no/such/dir/out.json")});
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Contains("cannot create a temporary file next to") && Contains("out.json"));
  // The table still went out before the failure.
  CHECK_THAT(r.out, Contains("RMSE"));
}
