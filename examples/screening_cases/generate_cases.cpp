// hbos-screening-cases: builds the labelled real residual cases (docs/screening_cases.md) from
// the bundled TUM fr1/xyz frames and the people of the fr3/walking_xyz frame in ../shared.
#include "case_builder.hpp"
#include "case_writer.hpp"
#include "common/atomic_file.hpp"
#include "common/tool_main.hpp"
#include "person_cutouts.hpp"

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <hbos/error.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using hbos::cases::CaseSpec;

/// The scene folders an earlier run's manifest lists (names only: a folder name never holds a
/// path separator or "..", so nothing outside `--out` is named). A manifest that cannot be read
/// is refused rather than overwritten, since its scenes are unknown.
std::vector<std::string> listed_scenes(const fs::path& manifest_path) {
  std::vector<std::string> names;
  try {
    std::ifstream in(manifest_path);
    const nlohmann::json manifest = nlohmann::json::parse(in);
    for (const auto& scene : manifest.at("scenes")) {
      const std::string name = scene.at("dir").get<std::string>();
      if (name.empty() || name == "." || name == ".." ||
          name.find_first_of("/\\") != std::string::npos)
        throw hbos::InvalidArgument(fmt::format("scene dir '{}' is not a folder name", name));
      names.push_back(name);
    }
  } catch (const std::exception& e) {
    throw hbos::InvalidArgument(
        fmt::format("{}: the earlier run's manifest cannot be read ({}); remove it to rebuild here",
                    manifest_path.string(), e.what()));
  }
  return names;
}

int run(int argc, char** argv) {
  CLI::App app{"Builds labelled reprojection-residual cases from real TUM frames.",
               "hbos-screening-cases"};
  std::string fr1 = (fs::path(HBOS_SLAM_DATA_DIR) / "fr1_xyz_37").string();
  std::string fr3, out, grid = "fixture", only, camera = "tum1";
  app.add_option("--fr1", fr1, "TUM folder of the static sequence (with groundtruth.txt)")
      ->capture_default_str();
  app.add_option("--camera", camera,
                 "intrinsics of --fr1: preset tum1 | tum3, or a .yaml/.yml/.json file")
      ->capture_default_str();
  app.add_option("--fr3", fr3,
                 "../shared/data/tum_fr3_dynaslam_yubaoliu (the people; not needed by --grid "
                 "static)");
  app.add_option("--grid", grid,
                 "which grid: fixture | holdout | static (the static scene alone, both ways)")
      ->check(CLI::IsMember({"fixture", "holdout", "static"}))
      ->capture_default_str();
  app.add_option("--out", out, "output folder (case folders and cases.json)")->required();
  app.add_option("--only", only, "build only the scene of this name (for inspection)");
  std::string preview;
  int preview_frame = 0;
  app.add_option("--preview", preview, "with --only: write frame --preview-frame as an image");
  app.add_option("--preview-frame", preview_frame, "frame index of --preview")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }

  if (fr3.empty() && grid != "static")
    throw hbos::InvalidArgument(fmt::format(
        "--fr3 is required for the {} grid: its scenes composite the people of that frame", grid));

  hbos::cases::CaseInputs inputs;
  inputs.sequence = hbos::slam::load_tum_sequence(fr1);
  if (inputs.sequence.unpaired_rgb > 0) {
    std::cerr << fmt::format(
        "hbos-screening-cases: warning: {} of {} colour images in {}/rgb.txt have no depth image "
        "within 0.02 s; they are skipped, so some pairs span a gap\n",
        inputs.sequence.unpaired_rgb, inputs.sequence.unpaired_rgb + inputs.sequence.size(), fr1);
  }
  inputs.camera = hbos::slam::load_camera(camera);
  // The static grid composites no one: its cases need no people, so no ../shared either.
  if (!fr3.empty()) inputs.people = hbos::cases::cut_people(fr3);
  const std::vector<CaseSpec> specs = grid == "fixture"   ? hbos::cases::fixture_grid()
                                      : grid == "holdout" ? hbos::cases::holdout_grid()
                                                          : hbos::cases::static_grid();
  bool found = only.empty();
  for (const CaseSpec& s : specs) found = found || s.name == only;
  if (!found) throw hbos::InvalidArgument(fmt::format("no case '{}' in the {} grid", only, grid));

  if (!preview.empty()) {
    if (only.empty()) throw hbos::InvalidArgument("--preview needs --only SCENE");
    // OpenCV throws for a name whose extension it has no writer for (p.txt).
    if (!cv::haveImageWriter(preview))
      throw hbos::InvalidArgument(fmt::format(
          "--preview '{}': no image format for its extension (use .png or .jpg)", preview));
    for (const CaseSpec& s : specs)
      if (s.name == only &&
          !cv::imwrite(preview, hbos::cases::preview_frame(s, inputs, preview_frame)))
        throw hbos::InvalidArgument(fmt::format("cannot write preview '{}'", preview));
    return 0;
  }
  {
    std::error_code error;
    fs::create_directories(out, error);
    if (error || !fs::is_directory(out))
      throw hbos::InvalidArgument(
          fmt::format("--out '{}': cannot create the folder: {}", out,
                      error ? error.message() : std::string("a file of that name exists")));
  }
  // A full run rewrites the scene folders in place: the old manifest goes first, so that a run
  // cut off midway leaves no cases.json vouching for a mix of new and old scenes (the readers
  // refuse a folder without one), and the scenes it listed that this grid no longer has go
  // last, before the new manifest is written.
  const fs::path manifest_path = fs::path(out) / "cases.json";
  std::vector<std::string> old_scenes;
  if (only.empty() && fs::exists(manifest_path)) {
    old_scenes = listed_scenes(manifest_path);
    std::error_code error;
    fs::remove(manifest_path, error);
    if (error)
      throw hbos::InvalidArgument(
          fmt::format("--out '{}': cannot remove the old cases.json: {}", out, error.message()));
  }
  nlohmann::ordered_json manifest;
  manifest["format"] = 1;
  manifest["grid"] = grid;
  manifest["sequence"] = fs::path(fr1).filename().string();
  // Absent means tum1, the camera of every case built before the option (their bytes unchanged).
  if (camera != "tum1") manifest["camera"] = inputs.camera.name;
  manifest["frames"] = inputs.sequence.size();
  manifest["gross_sigmas"] = hbos::cases::kGrossSigmas;
  manifest["on_mask_px"] = hbos::cases::kOnMaskPx;
  nlohmann::ordered_json people = nlohmann::ordered_json::array();
  for (const auto& p : inputs.people) {
    people.push_back({{"person", std::string(1, p.id)},
                      {"box_px", {p.box.x, p.box.y, p.box.width, p.box.height}},
                      {"pixels", p.pixels},
                      {"source_median_depth_m", p.median_depth_m}});
  }
  manifest["source_people"] = people;
  manifest["columns"] = hbos::cases::pair_csv_header();
  nlohmann::ordered_json scenes = nlohmann::ordered_json::array();
  nlohmann::ordered_json cases = nlohmann::ordered_json::array();
  for (const CaseSpec& spec : specs) {
    if (!only.empty() && spec.name != only) continue;
    const auto pairs = hbos::cases::build_case(spec, inputs);
    scenes.push_back(hbos::cases::write_case((fs::path(out) / spec.name).string(), spec, pairs));
    // Each scene is two cases: the same matches under the RANSAC and the perturbed-GT pose.
    for (const auto kind :
         {hbos::cases::RoughPoseKind::kRansac, hbos::cases::RoughPoseKind::kPerturbed}) {
      nlohmann::ordered_json who = nlohmann::ordered_json::array();
      for (const auto& p : spec.people) who.push_back(std::string(1, p.person));
      cases.push_back({{"name", spec.name + "_" + hbos::cases::to_string(kind)},
                       {"dir", spec.name},
                       {"people", who},
                       {"speed", spec.speed},
                       {"mask", hbos::cases::to_string(spec.mask)},
                       {"rough_pose", hbos::cases::to_string(kind)},
                       {"seed", kind == hbos::cases::RoughPoseKind::kPerturbed ? spec.seed : 0},
                       {"pairs", pairs.size()}});
    }
    std::size_t matches = 0, dynamic = 0, gross = 0;
    double max_share = 0.0;
    for (const auto& p : pairs) {
      std::size_t d = 0;
      for (const auto& r : p.rows) {
        d += r.dynamic ? 1 : 0;
        gross += r.gross ? 1 : 0;
      }
      matches += p.rows.size();
      dynamic += d;
      if (!p.rows.empty())
        max_share =
            std::max(max_share, static_cast<double>(d) / static_cast<double>(p.rows.size()));
    }
    std::cerr << fmt::format(
        "{:28} {:2} pairs, {:5.0f} matches/pair, dynamic {:5.1f} % (max "
        "{:4.1f} %), gross {:4.2f} %\n",
        spec.name, pairs.size(), static_cast<double>(matches) / static_cast<double>(pairs.size()),
        100.0 * static_cast<double>(dynamic) / static_cast<double>(matches), 100.0 * max_share,
        100.0 * static_cast<double>(gross) / static_cast<double>(matches));
  }
  manifest["cases"] = cases;
  manifest["scenes"] = scenes;
  if (only.empty()) {
    for (const std::string& scene : old_scenes) {
      const bool kept = std::any_of(specs.begin(), specs.end(),
                                    [&](const CaseSpec& spec) { return spec.name == scene; });
      if (!kept) {
        fs::remove_all(fs::path(out) / scene);
        std::cerr << fmt::format("removed scene '{}': not in the {} grid\n", scene, grid);
      }
    }
    hbos::examples::write_file_atomically(manifest_path, manifest.dump(1) + "\n");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return hbos::examples::run_tool("hbos-screening-cases", [&] { return run(argc, argv); });
}
