// The benchmark end to end: the grid, the table over seeds, resuming finished cells, and (when
// hbos-render is built) a short rendered scenario through the whole command.

#include <catch2/catch.hpp>

#include "dynbench/cells.hpp"
#include "dynbench/dynbench_command.hpp"
#include "dynbench/sequences.hpp"
#include "dynbench/summary.hpp"
#include "test_frontend_support.hpp"
#include "tum_folder.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

using hbos_test::ScratchDir;
namespace fs = std::filesystem;

namespace {

int dynbench(const std::vector<std::string>& args, std::string* out_text = nullptr,
             std::string* err_text = nullptr) {
  std::vector<const char*> argv = {"hbos-dynbench"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  const int rc =
      hbos::dynbench::run_dynbench_command(static_cast<int>(argv.size()), argv.data(), out, err);
  if (out_text != nullptr) *out_text = out.str();
  if (err_text != nullptr) *err_text = err.str();
  return rc;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const nlohmann::json* row_of(const nlohmann::json& table, const std::string& mask,
                             const std::string& screen) {
  for (const auto& r : table["rows"]) {
    if (r["mask"] == mask && r["screen"] == screen) return &r;
  }
  return nullptr;
}

}  // namespace

TEST_CASE("dynbench grid: cells, names and screens", "[dynbench]") {
  hbos::dynbench::BenchSettings s;
  s.scenarios = {"walking_xyz"};
  s.seeds = {1, 2};
  s.variants = {"eroded", "boxes"};
  const auto cells = hbos::dynbench::grid_cells(s);
  // Per seed: none and default without a mask, then every screen (7) with each of 2 variants.
  CHECK(cells.size() == 2 * (2 + 2 * hbos::dynbench::screens_in_order({}).size()));
  CHECK(cells.front().id() == "walking_xyz_s1_none_none");
  CHECK(cells[1].id() == "walking_xyz_s1_none_default");
  CHECK(cells[2].id() == "walking_xyz_s1_eroded_none");
  s.every_screen_unmasked = true;
  const auto unmasked = hbos::dynbench::grid_cells(s);
  // Per seed: every screen without a mask too.
  CHECK(unmasked.size() == 2 * 3 * hbos::dynbench::screens_in_order({}).size());
  CHECK(unmasked[1].id() == "walking_xyz_s1_none_fixed");
  s.screens = {"chi2", "default"};
  const auto chosen = hbos::dynbench::grid_cells(s);
  CHECK(chosen.size() == 2 * 3 * 2);
  CHECK(chosen.front().id() == "walking_xyz_s1_none_chi2");
  s.screens.clear();
  s.every_screen_unmasked = false;
  const auto order = hbos::dynbench::screens_in_order({"default", "chi2", "none"});
  CHECK(order == std::vector<std::string>{"none", "chi2", "default"});
  CHECK_THROWS_WITH(hbos::dynbench::screens_in_order({"hbos"}), Catch::Contains("'hbos'"));
  hbos::dynbench::use_full_grid(s);
  CHECK(s.scenarios.size() == 6);
  CHECK(s.variants.size() == 8);
  CHECK(s.frames == 0);
}

TEST_CASE("dynbench cells: the opt-in front-end settings are part of a cell's key", "[dynbench]") {
  hbos::dynbench::BenchSettings s;
  s.base.tracker = hbos::slam::TrackerKind::kMap;
  const hbos::dynbench::Cell cell{"walking_xyz", 1, "eroded", "default"};
  const auto plain = hbos::dynbench::cell_settings(s, cell, "fingerprint");
  CHECK(plain.at("local_bundle_adjustment") == false);
  CHECK(plain.at("huber_from_noise") == false);
  s.base.map.local_bundle.enabled = true;
  const auto adjusted = hbos::dynbench::cell_settings(s, cell, "fingerprint");
  CHECK(adjusted.at("local_bundle_adjustment") == true);
  // A finished cell is reused only when its stored settings equal these: a run with the
  // adjustment never takes a cell made without it.
  CHECK(adjusted != plain);
  // The new points' own consensus is on by default; a run without it keeps cells of its own.
  CHECK(plain.at("provisional_consensus") == true);
  s.base.screen.provisional_consensus = false;
  const auto without_consensus = hbos::dynbench::cell_settings(s, cell, "fingerprint");
  CHECK(without_consensus != adjusted);
  // The later rounds' gate floor keys them too, as the tracker resolves it: cells of one floor
  // are never taken for another.
  CHECK(plain.at("later_rounds_gate_floor") == hbos::slam::later_rounds_gate_floor(s.base));
  s.base.screen.later_rounds_gate_floor = 1.5;
  const auto lower_floor = hbos::dynbench::cell_settings(s, cell, "fingerprint");
  CHECK(lower_floor.at("later_rounds_gate_floor") == 1.5);
  CHECK(lower_floor != without_consensus);
  // So does the later rounds' field model.
  CHECK(plain.at("later_rounds_rigid_field") == hbos::slam::later_rounds_rigid_field(s.base));
  s.base.screen.later_rounds_rigid_field = !hbos::slam::later_rounds_rigid_field(s.base);
  const auto other_field = hbos::dynbench::cell_settings(s, cell, "fingerprint");
  CHECK(other_field.at("later_rounds_rigid_field") == *s.base.screen.later_rounds_rigid_field);
  CHECK(other_field != lower_floor);
}

TEST_CASE("dynbench cells: the relocaliser's refit check keys the map tracker's cells alone",
          "[dynbench]") {
  hbos::dynbench::BenchSettings s;
  const hbos::dynbench::Cell cell{"walking_xyz", 1, "eroded", "default"};
  s.base.tracker = hbos::slam::TrackerKind::kMap;
  const auto checked = hbos::dynbench::cell_settings(s, cell, "fingerprint");
  CHECK(checked.at("relocaliser_refit_check") == true);
  s.base.map.relocalisation.check_refit = false;
  CHECK(hbos::dynbench::cell_settings(s, cell, "fingerprint") != checked);
  // The frame tracker never relocalises: its cells keep the keys they had before the check.
  s.base.tracker = hbos::slam::TrackerKind::kFrame;
  const auto frame = hbos::dynbench::cell_settings(s, cell, "fingerprint");
  CHECK_FALSE(frame.contains("relocaliser_refit_check"));
  s.base.map.relocalisation.check_refit = true;
  CHECK(hbos::dynbench::cell_settings(s, cell, "fingerprint") == frame);
}

TEST_CASE("dynbench cells: a camera file's numbers, not only its name, are part of a cell's key",
          "[dynbench]") {
  const fs::path dir = fs::temp_directory_path() / "hbos_dynbench_camera_key";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path camera = dir / "camera.yaml";
  const auto write_camera = [&](double fx) {
    std::ofstream(camera) << "fx: " << fx << "\nfy: 539.2\ncx: 320.1\ncy: 247.6\n";
  };
  hbos::dynbench::BenchSettings s;
  s.camera = camera.string();
  const hbos::dynbench::Cell cell{"walking_xyz", 1, "eroded", "default"};
  write_camera(535.4);
  const auto before = hbos::dynbench::cell_settings(s, cell, "fingerprint");
  CHECK(before.at("camera_model").at("fx") == 535.4);
  // The same file name with other intrinsics: a finished cell of the first must not be reused.
  write_camera(300.0);
  const auto after = hbos::dynbench::cell_settings(s, cell, "fingerprint");
  CHECK(after.at("camera") == before.at("camera"));
  CHECK(after != before);
  fs::remove_all(dir);
}

TEST_CASE("dynbench spread: mean and sample standard deviation, NaN left out", "[dynbench]") {
  const auto s = hbos::dynbench::spread_of({1.0, 3.0, std::nan("")});
  CHECK(s.n == 2);
  CHECK(s.mean == Approx(2.0));
  CHECK(s.sd == Approx(std::sqrt(2.0)));
  CHECK(hbos::dynbench::spread_of({}).n == 0);
}

TEST_CASE("dynbench on a prepared sequence: table, JSON, figures, and resuming", "[dynbench]") {
  // The fr1/xyz frames with the composited person stand in for a rendered walking_xyz sequence:
  // put into the cache, they are used as they are, with no renderer.
  ScratchDir scratch("dynbench_prepared");
  hbos::dynbench::BenchSettings s;
  s.cache_dir = scratch.file("cache");
  s.frames = 10;
  const std::string sequence = hbos::dynbench::sequence_dir(s, "walking_xyz", 1);
  hbos_test::write_tum_folder(sequence, 10);
  const std::vector<std::string> args = {"--scenarios", "walking_xyz",
                                         "--seeds",     "1",
                                         "--frames",    "10",
                                         "--variants",  "eroded",
                                         "--screens",   "none,default",
                                         "--camera",    "tum1",
                                         "--renderer",  "",
                                         "--cache",     s.cache_dir,
                                         "--out",       scratch.file("out"),
                                         "--jobs",      "2",
                                         "--quiet"};
  std::string out, err;
  REQUIRE(dynbench(args, &out, &err) == hbos::dynbench::kDynbenchOk);
  INFO(err);
  CHECK_THAT(out, Catch::Contains("| walking_xyz | eroded | default |"));
  CHECK_THAT(out, Catch::Contains("Table III"));
  const fs::path root = scratch.path() / "out";
  const auto table = nlohmann::json::parse(read_text(root / "dynbench.json"));
  REQUIRE(table["rows"].size() == 4);  // none, default alone, mask only, mask + default
  const auto* unmasked = row_of(table, "none", "none");
  const auto* screened = row_of(table, "none", "default");
  const auto* masked = row_of(table, "eroded", "none");
  REQUIRE(unmasked != nullptr);
  REQUIRE(screened != nullptr);
  REQUIRE(masked != nullptr);
  // The objects/ labels count the person's matches: all kept without a screen, fewer with the
  // eroded mask (which leaks only along the edges), and the screen removes some.
  CHECK((*unmasked)["dynamic_matches"].get<long>() > 50);
  CHECK((*unmasked)["dynamic_matches_kept_pct"]["mean"].get<double>() == Approx(100.0));
  CHECK((*masked)["dynamic_matches"].get<long>() < (*unmasked)["dynamic_matches"].get<long>());
  CHECK((*screened)["dynamic_matches_kept_pct"]["mean"].get<double>() < 100.0);
  CHECK((*unmasked)["ate_rmse_cm"]["n"] == 1);
  CHECK(fs::is_regular_file(root / "dynbench.md"));
  CHECK(fs::is_regular_file(root / "figures" / "trajectories.png"));
  CHECK(fs::is_regular_file(root / "figures" / "residual_histogram.png"));
  CHECK(fs::is_regular_file(root / "figures" / "matches_mask.png"));

  // Re-run: every cell is taken from its cell.json, unchanged.
  const fs::path cell = root / "cells" / "walking_xyz_s1_eroded_default" / "cell.json";
  const fs::path other = root / "cells" / "walking_xyz_s1_none_none" / "cell.json";
  const std::string before = read_text(cell), before_other = read_text(other);
  REQUIRE(dynbench(args, &out, &err) == hbos::dynbench::kDynbenchOk);
  CHECK(read_text(cell) == before);
  // An unfinished cell (no cell.json: interrupted) is run again; the finished ones are not.
  fs::remove(cell);
  REQUIRE(dynbench(args, &out, &err) == hbos::dynbench::kDynbenchOk);
  CHECK(fs::is_regular_file(cell));
  CHECK(read_text(other) == before_other);
  // Other settings are other cells: they are run again.
  std::vector<std::string> two_rounds = args;
  two_rounds.insert(two_rounds.end(), {"--rounds", "2"});
  REQUIRE(dynbench(two_rounds, &out, &err) == hbos::dynbench::kDynbenchOk);
  CHECK(read_text(other) != before_other);
}

TEST_CASE("dynbench: bad input exits 2 with the reason", "[dynbench]") {
  ScratchDir scratch("dynbench_bad");
  std::string err;
  CHECK(dynbench({"--scenarios", "walking_upside_down", "--quiet"}, nullptr, &err) ==
        hbos::dynbench::kDynbenchBadInput);
  CHECK_THAT(err, Catch::Contains("walking_upside_down"));
  CHECK(dynbench({"--screens", "hbos", "--quiet", "--out", scratch.file("o")}, nullptr, &err) ==
        hbos::dynbench::kDynbenchBadInput);
  CHECK_THAT(err, Catch::Contains("'hbos'"));
  CHECK(dynbench(
            {"--renderer", scratch.file("no-such-renderer"), "--out", scratch.file("o"), "--quiet"},
            nullptr, &err) == hbos::dynbench::kDynbenchBadInput);
  CHECK_THAT(err, Catch::Contains("no-such-renderer"));
  // Seeds: "-1" wrapped to 2^64 - 1, a number past 2^64 - 1 was clamped to it, '' ran seed 0.
  for (const char* seeds : {"-1", "99999999999999999999", "", "1,x"}) {
    err.clear();
    CHECK(dynbench({"--seeds", seeds, "--quiet", "--out", scratch.file("o")}, nullptr, &err) ==
          hbos::dynbench::kDynbenchBadInput);
    CHECK_THAT(err, Catch::Contains("a seed is a decimal integer"));
  }
  // An empty --out wrote into the current folder.
  err.clear();
  CHECK(dynbench({"--out", "", "--quiet"}, nullptr, &err) == hbos::dynbench::kDynbenchBadInput);
  CHECK_THAT(err, Catch::Contains("an empty path names no file"));
}

TEST_CASE("dynbench --people renders its own sequences, cached apart", "[dynbench]") {
  ScratchDir scratch("dynbench_people");
  hbos::dynbench::BenchSettings s;
  s.cache_dir = "cache";
  CHECK(fs::path(hbos::dynbench::sequence_dir(s, "walking_xyz", 4)).filename() ==
        "walking_xyz_seed4_300f");  // the scenario's own cast: the name caches always had
  s.people = 3;
  CHECK(fs::path(hbos::dynbench::sequence_dir(s, "walking_xyz", 4)).filename() ==
        "walking_xyz_seed4_300f_3people");

  // A stand-in renderer that fails: the error names the command it was given.
  const std::string renderer = scratch.file("failing-renderer.sh");
  {
    std::ofstream script(renderer);
    script << "#!/bin/sh\necho \"stand-in renderer: $*\"\nexit 3\n";
  }
  fs::permissions(renderer, fs::perms::owner_all);
  std::string err;
  CHECK(dynbench({"--scenarios", "walking_rpy", "--seeds", "2", "--frames", "5", "--people", "3",
                  "--renderer", renderer, "--cache", scratch.file("cache"), "--out",
                  scratch.file("out"), "--quiet"},
                 nullptr, &err) != hbos::dynbench::kDynbenchOk);
  CHECK_THAT(err,
             Catch::Contains("--scenario walking_rpy --seed 2 --out ") &&
                 Catch::Contains("walking_rpy_seed2_5f_3people --frames 5 --quiet --people 3"));

  for (const char* people : {"0", "4", "two"}) {
    err.clear();
    CHECK(dynbench({"--people", people, "--quiet", "--out", scratch.file("o")}, nullptr, &err) ==
          hbos::dynbench::kDynbenchBadInput);
    CHECK_THAT(err, Catch::Contains("--people"));
  }
}

TEST_CASE("dynbench --help names the front end's on/off settings and their defaults",
          "[dynbench]") {
  std::string out, err;
  REQUIRE(dynbench({"--help"}, &out, &err) == hbos::dynbench::kDynbenchOk);
  const std::string help = out + err;
  // The options it shares with hbos-slam (frontend/config_options.hpp), defaults included.
  const std::size_t local_ba = help.find("--local-ba,--no-local-ba");
  REQUIRE(local_ba != std::string::npos);
  CHECK(help.find("(default: off)", local_ba) < help.find("--huber-from-noise", local_ba));
  const std::size_t evidence = help.find("--mask-evidence,--no-mask-evidence");
  REQUIRE(evidence != std::string::npos);
  CHECK(help.find("(default: on)", evidence) < help.find("--track-history", evidence));
  const std::size_t consensus = help.find("--provisional-consensus,--no-provisional-consensus");
  REQUIRE(consensus != std::string::npos);
  CHECK(help.find("(default: on)", consensus) < help.find("--history-consensus", consensus));
  CHECK_THAT(help, Catch::Contains("--rounds"));
  const std::size_t later = help.find("--later-rounds-floor");
  REQUIRE(later != std::string::npos);
  CHECK(help.find("the tracker's own", later) < help.find("--rounds", later));
  const std::size_t field = help.find("--later-rounds-field");
  REQUIRE(field != std::string::npos);
  CHECK(help.find("default: rigid, for both trackers", field) != std::string::npos);
}

TEST_CASE("dynbench end to end on a short rendered scenario", "[dynbench][render]") {
  const std::string renderer = hbos::dynbench::built_renderer();
  if (renderer.empty() || !fs::is_regular_file(renderer)) {
    WARN("hbos-render is not built (OSMesa missing): the rendered end-to-end test is skipped");
    return;
  }
  ScratchDir scratch("dynbench_rendered");
  std::string out, err;
  const int rc =
      dynbench({"--scenarios", "walking_xyz", "--seeds", "1", "--frames", "20", "--variants",
                "perfect", "--screens", "none,default", "--out", scratch.file("out"), "--quiet"},
               &out, &err);
  INFO(err);
  REQUIRE(rc == hbos::dynbench::kDynbenchOk);
  const auto table = nlohmann::json::parse(read_text(scratch.path() / "out" / "dynbench.json"));
  REQUIRE(table["rows"].size() == 4);
  const auto* unmasked = row_of(table, "none", "none");
  const auto* masked = row_of(table, "perfect", "none");
  REQUIRE(unmasked != nullptr);
  REQUIRE(masked != nullptr);
  // The rendered people are in view and labelled; the perfect mask leaves (almost) none.
  CHECK((*unmasked)["dynamic_matches"].get<long>() > 0);
  CHECK((*masked)["dynamic_matches"].get<long>() < (*unmasked)["dynamic_matches"].get<long>());
  CHECK((*unmasked)["frames_tracked_pct"]["mean"].get<double>() > 50.0);
}
