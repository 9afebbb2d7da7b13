#include "frontend/slam_command.hpp"

#include "common/atomic_file.hpp"
#include "common/cli_validators.hpp"
#include "common/stop_on_signal.hpp"
#include "frontend/ablation.hpp"
#include "frontend/camera.hpp"
#include "frontend/config.hpp"
#include "frontend/config_options.hpp"
#include "frontend/dataset.hpp"
#include "frontend/frame_source.hpp"
#include "frontend/grid/grid_command.hpp"
#include "frontend/map/map_report.hpp"
#include "frontend/map/map_run.hpp"
#include "frontend/mask_files.hpp"
#include "frontend/orb_extraction.hpp"
#include "frontend/residual_screen.hpp"
#include "frontend/run_outputs.hpp"
#include "frontend/sequence_run.hpp"

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <hbos/error.hpp>

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>

namespace hbos::slam {

namespace {

/// The embedded data, found next to the sources (examples/slam/data).
std::string embedded(const char* relative) {
  return (std::filesystem::path(HBOS_SLAM_DATA_DIR) / relative).string();
}

struct CommandOptions {
  Config config;
  std::string scenario = "person";
  std::string mask = "degraded";
  std::string rough_pose = "ransac";
  std::string tracker = "frame";
  std::string mask_convention = "dynaslam";  ///< of --mask-dir's files
  bool quiet = false;
  bool ablation = false;
  bool variant_grid = false;
};

void add_options(CLI::App& app, CommandOptions& o) {
  Config& c = o.config;
  app.add_option("--dataset", c.dataset.path,
                 "TUM RGB-D folder (rgb.txt, depth.txt[, groundtruth.txt])")
      ->capture_default_str();
  app.add_option("--camera", c.dataset.camera,
                 "intrinsics: preset tum1 | tum3, or a .yaml/.yml/.json file")
      ->capture_default_str();
  app.add_option("--frames", c.dataset.max_frames, "use only the first N frames (0 = all)")
      ->capture_default_str()
      ->check(examples::non_negative_number());
  app.add_option("--scenario", o.scenario,
                 "static: the sequence as recorded; person: a real person composited in")
      ->capture_default_str()
      ->check(CLI::IsMember({"static", "person"}));
  app.add_option("--person-dir", c.scenario.person_dir,
                 "person cut-out (rgb.png, mask.png, depth.png)")
      ->capture_default_str();
  // A depth sensor's range, wide: 1e-300 m or 1e300 m ran, on a person scaled to nothing.
  app.add_option("--person-depth", c.scenario.depth_m, "median depth of the person [m], 0.2 to 20")
      ->capture_default_str()
      ->check(CLI::Range(0.2, 20.0));
  app.add_option("--person-start", c.scenario.start_x_px, "left edge of the person in frame 0 [px]")
      ->capture_default_str();
  app.add_option("--person-speed", c.scenario.speed_px_per_frame,
                 "sideways motion of the person [px/frame]")
      ->capture_default_str();
  app.add_option("--mask", o.mask, "dynamic-object mask the features avoid")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "exact", "degraded", "detector", "files"}));
  app.add_option("--mask-dir", c.mask.files_dir,
                 "masks from files, one per frame matched by rgb file name or stamp (implies "
                 "--mask files and, unless given, --scenario static)");
  app.add_option("--mask-convention", o.mask_convention,
                 "--mask-dir files: dynaslam (0 = dynamic) or nonzero-dynamic")
      ->capture_default_str()
      ->check(CLI::IsMember({"dynaslam", "nonzero-dynamic"}));
  app.add_option("--detector-dir", c.mask.detector_dir,
                 "folder with yolo-fastest-1.1_body.cfg and .weights")
      ->capture_default_str();
  app.add_option_function<std::string>(
         "--screen", [&c](const std::string& name) { c.screen.select(name); },
         "residual screen (default: " + c.screen.name + ")")
      ->check(CLI::IsMember(screen_strategy_names()));
  add_front_end_options(app, c);
  app.add_option("--huber-width", c.refinement.huber_delta,
                 "the pose refinement's Huber width [px/sigma] (ORB-SLAM2's sqrt(5.991)); 0 = "
                 "plain least squares")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  app.add_option("--rough-pose", o.rough_pose, "how the rough pose is found")
      ->capture_default_str()
      ->check(CLI::IsMember({"ransac", "constant-velocity"}));
  app.add_option("--ransac-px", c.rough_pose.ransac_threshold_px,
                 "PnP RANSAC inlier threshold [px]")
      ->capture_default_str()
      ->check(examples::positive_number());
  app.add_option("--features", c.extraction.features, "ORB features per frame (1 to 100000)")
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxOrbFeatures));
  app.add_option("--orb-spread-px", c.extraction.spread_cell_px,
                 "spread the ORB features over cells of this side [px] per pyramid level, from a "
                 "pool of --orb-spread-pool times --features (as ORB-SLAM2 spreads them); 0 = "
                 "cv::ORB's strongest corners of the whole frame")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10000.0));
  app.add_option("--orb-spread-pool", c.extraction.spread_pool,
                 "with --orb-spread-px: the pool detected, in multiples of --features (1 to 10)")
      ->capture_default_str()
      ->check(CLI::Range(1, 10));
  app.add_option("--out", c.output.dir, "output folder")->capture_default_str();
  app.add_option("--figure-frame", c.output.figure_frame,
                 "frame drawn in matches.png / residual_histogram.png (-1: most person matches)")
      ->capture_default_str()
      ->check(CLI::Range(-1, 1000000));
  app.add_option("--tracker", o.tracker,
                 "frame: frame-to-frame odometry; map: tracking against a local map of keyframes "
                 "(docs/map_tracking.md)")
      ->capture_default_str()
      ->check(CLI::IsMember({"frame", "map"}));
  app.add_flag("--quiet", o.quiet, "no per-frame progress on stderr");
  app.add_flag("--ablation", o.ablation,
               "run every screen x mask on the static and the person scenario and write "
               "ablation.md and ablation.csv into --out");
  app.add_flag("--variant-grid", o.variant_grid,
               "run every screen under masks none, degraded and detector on 8 semi-real variants "
               "of the person's path with --tracker, and write variant_grid_<tracker>.md and "
               ".json into --out (finished runs are kept in --out/variant_grid_runs and reused)")
      ->excludes("--ablation");
}

// ---- Ctrl-C: stop after the frame in progress and write what the run has --------------------

using hbos::examples::StopOnSignal;

// ---- checks before the run ----------------------------------------------------------------

/// Creates the output folder and proves it writable with a probe file, so that a run is not
/// wasted on an output that cannot be written.
void prepare_output_dir(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::exists(dir, error) && !fs::is_directory(dir, error)) {
    throw InvalidArgument(fmt::format("--out '{}' exists and is not a directory", dir));
  }
  fs::create_directories(dir, error);
  if (error) {
    throw InvalidArgument(fmt::format("--out '{}': cannot create: {}", dir, error.message()));
  }
  std::string probe = (fs::path(dir) / ".hbos-slam-probe-XXXXXX").string();
  const int fd = ::mkstemp(probe.data());
  if (fd < 0) {
    throw InvalidArgument(fmt::format("--out '{}' is not writable: {}", dir, std::strerror(errno)));
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

/// Everything a run needs, checked before its first frame: every image of the frames to run
/// exists and opens, the first frame decodes and the camera's principal point lies inside it,
/// and --out can be written.
void check_run_inputs(const Config& config, const CameraModel& camera,
                      const RgbdSequence& sequence) {
  check_sequence_files(sequence, config.dataset.max_frames);
  const RgbdImages first = read_frame_images(sequence, 0, camera.depth_factor);
  check_camera_fits_image(
      camera, first.bgr.cols, first.bgr.rows,
      (std::filesystem::path(sequence.root) / sequence.frames[0].rgb.path).string());
  prepare_output_dir(config.output.dir);
}

std::string percent_or_na(const std::optional<double>& share) {
  return share ? fmt::format("{:.1f} %", 100.0 * *share) : std::string("n/a");
}

int run_single(const CommandOptions& o, const CameraModel& camera, const RgbdSequence& sequence,
               std::ostream& out, std::ostream& err) {
  const Config& config = o.config;
  FrameSource source(sequence, camera.depth_factor, config.scenario, config.mask);
  int n = source.size();
  if (config.dataset.max_frames > 0) n = std::min(n, config.dataset.max_frames);
  if (config.output.figure_frame >= n) {
    throw InvalidArgument(fmt::format("--figure-frame {} is beyond the {} frames run",
                                      config.output.figure_frame, n));
  }
  check_run_inputs(config, camera, sequence);
  const StopOnSignal stop_on_signal;
  std::optional<MapRun> map_run;  // --tracker map: the run and what only the map tracker measures
  RunResult frame_run;
  if (config.tracker == TrackerKind::kMap) {
    // A bar redrawn in place on a terminal, one line per frame in a log.
    const bool terminal = &err == &std::cerr && ::isatty(STDERR_FILENO) == 1;
    map_run = run_map_tracker(
        [&](int i) { return source.frame(i); }, n, config, camera, o.quiet ? nullptr : &err,
        terminal ? ProgressStyle::kBar : ProgressStyle::kLines, StopOnSignal::flag());
  } else {
    frame_run = run_tracker([&](int i) { return source.frame(i); }, n, config, camera,
                            o.quiet ? nullptr : &err, StopOnSignal::flag());
  }
  RunResult& run = map_run ? map_run->run : frame_run;
  if (run.input_error) {
    // The frames before the bad one are kept, as on Ctrl-C; the exit status says bad input.
    err << fmt::format("hbos-slam: error: {}\nhbos-slam: stopped at frame {} of {}; {}\n",
                       *run.input_error, run.stats.size() + 1, n,
                       run.stats.empty() ? "nothing to write" : "writing the frames before it");
    if (run.stats.empty()) return kSlamBadInput;
  }
  const bool interrupted = !run.input_error && StopOnSignal::stopped();
  if (interrupted) {
    err << fmt::format("hbos-slam: interrupted after {} of {} frames; writing them\n",
                       run.stats.size(), n);
    if (run.stats.empty()) return kSlamInterrupted;
  }
  const Trajectory* groundtruth = sequence.groundtruth ? &*sequence.groundtruth : nullptr;
  if (groundtruth != nullptr) {
    try {
      run.evaluation = evaluate_trajectory(*groundtruth, estimate_of(run, "hbos-slam"), run.stamps);
    } catch (const InvalidArgument& e) {
      // E.g. too few frames for the RPE: the run's own outputs are still worth writing.
      err << "hbos-slam: warning: not evaluated: " << e.what() << "\n";
      groundtruth = nullptr;
    }
  }

  const RunTotals& t = run.totals;
  out << fmt::format(
      "hbos-slam: {} frames of {} | {} scenario, mask {}, screen {}, rough pose {}\n",
      run.stats.size(), config.dataset.path, scenario_name(config.scenario),
      to_string(config.mask.source), config.screen.name, to_string(config.rough_pose.method));
  if (run.evaluation) {
    const Evaluation& e = *run.evaluation;
    out << fmt::format("  ATE RMSE {:.2f} cm (mean {:.2f}, max {:.2f}) over {} poses",
                       100.0 * e.ate.stats.rmse, 100.0 * e.ate.stats.mean, 100.0 * e.ate.stats.max,
                       e.ate.stats.count);
    if (e.rpe) {
      out << fmt::format("; RPE {:.2f} mm/frame, {:.3f} deg/frame (RMSE)",
                         1000.0 * e.rpe->trans_m.rmse, e.rpe->rot_deg.rmse);
    }
    out << "\n";
  } else {
    out << "  ATE/RPE not computed (no groundtruth.txt, or see the warning)\n";
  }
  out << fmt::format(
      "  matches {:.0f}/frame; person matches kept {} ({} of {}); static matches lost {:.1f} %; "
      "screen {:.0f} us/frame (median {:.0f}), refinement {:.0f} us/frame, mask {:.1f} ms/frame; "
      "{} of {} frames tracked\n",
      t.frames > 1 ? static_cast<double>(t.matches) / (t.frames - 1) : 0.0,
      percent_or_na(t.person_survival_share), t.person_survivors, t.person_matches,
      100.0 * t.static_loss_share, t.mean_screen_us, t.median_screen_us, t.mean_refine_us,
      t.mean_mask_us / 1000.0, t.frames_tracked, t.frames);
  if (map_run) out << map_summary_text(*map_run);
  try {
    std::vector<std::string> written =
        write_run_outputs(config.output.dir, run, config, camera.name, groundtruth);
    if (map_run) {
      for (std::string& path : write_map_outputs(config.output.dir, *map_run))
        written.push_back(std::move(path));
    }
    for (const std::string& path : written) out << "wrote " << path << "\n";
    for (const std::string& path : remove_stale_outputs(config.output.dir, written))
      out << "removed " << path << " (an earlier run's; this run did not write it)\n";
  } catch (const std::runtime_error& e) {
    err << "hbos-slam: error: " << e.what() << "\n";
    return interrupted ? kSlamInterrupted : kSlamOutputError;
  }
  if (run.input_error) return kSlamBadInput;
  return interrupted ? kSlamInterrupted : kSlamOk;
}

int run_ablation_command(const CommandOptions& o, const CameraModel& camera,
                         const RgbdSequence& sequence, std::ostream& out, std::ostream& err) {
  const Config& config = o.config;
  const std::vector<AblationRow> rows =
      run_ablation(config, sequence, camera, o.quiet ? nullptr : &err);
  int n = static_cast<int>(sequence.size());
  if (config.dataset.max_frames > 0) n = std::min(n, config.dataset.max_frames);
  const std::string md = ablation_markdown(rows, config, camera.name, n);
  out << md;
  try {
    std::error_code error;
    std::filesystem::create_directories(config.output.dir, error);
    if (error)
      throw std::runtime_error("cannot create '" + config.output.dir + "': " + error.message());
    const auto md_path = (std::filesystem::path(config.output.dir) / "ablation.md").string();
    const auto csv_path = (std::filesystem::path(config.output.dir) / "ablation.csv").string();
    examples::write_file_atomically(md_path, md);
    examples::write_file_atomically(csv_path, ablation_csv(rows));
    out << "wrote " << md_path << "\nwrote " << csv_path << "\n";
  } catch (const std::runtime_error& e) {
    err << "hbos-slam: error: " << e.what() << "\n";
    return kSlamOutputError;
  }
  return kSlamOk;
}

}  // namespace

int run_slam_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  CLI::App app{
      "Mini-SLAM front end with a reprojection-residual screen (HBOS or a baseline). With no "
      "options it tracks the embedded 37 TUM fr1/xyz frames with a real person composited in, "
      "and writes trajectory.txt, stats.csv, summary.json and PNG figures into out/slam. Exit "
      "status: 0 ok, 1 output not written, 2 bad input.",
      "hbos-slam"};
  CommandOptions options;
  options.config.dataset.path = embedded("fr1_xyz_37");
  options.config.scenario.person_dir = embedded("person");
  options.config.mask.detector_dir = embedded("models/yolo-fastest-1.1_body");
  add_options(app, options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e, out, err) == 0 ? kSlamOk : kSlamBadInput;
  }
  if (!options.config.mask.files_dir.empty()) {
    // Masks from files come with their own sequence: nothing is composited unless asked.
    if (app.count("--mask") > 0 && options.mask != "files") {
      err << "hbos-slam: error: --mask-dir needs --mask files (or no --mask), got --mask "
          << options.mask << "\n";
      return kSlamBadInput;
    }
    options.mask = "files";
    if (app.count("--scenario") == 0) options.scenario = "static";
  } else if (options.mask == "files") {
    err << "hbos-slam: error: --mask files needs --mask-dir DIR\n";
    return kSlamBadInput;
  }
  options.config.mask.files_convention = parse_mask_convention(options.mask_convention);
  options.config.mask.files_max_difference = options.config.dataset.max_association_difference;
  options.config.scenario.add_person = options.scenario == "person";
  options.config.mask.source = parse_mask_source(options.mask);
  options.config.rough_pose.method = parse_rough_pose_method(options.rough_pose);
  options.config.tracker = options.tracker == "map" ? TrackerKind::kMap : TrackerKind::kFrame;
  options.config.output.progress = !options.quiet;
  try {
    const CameraModel camera = load_camera(options.config.dataset.camera);
    const RgbdSequence sequence = load_tum_sequence(
        options.config.dataset.path, options.config.dataset.max_association_difference);
    if (sequence.unpaired_rgb > 0) {
      // Skipped frames are a gap the tracker bridges as one long step: say so.
      err << fmt::format(
          "hbos-slam: warning: {} of {} colour images in {}/rgb.txt have no depth image within "
          "{} s; they are skipped\n",
          sequence.unpaired_rgb, sequence.unpaired_rgb + sequence.size(),
          options.config.dataset.path, options.config.dataset.max_association_difference);
    }
    if (options.variant_grid) {
      check_run_inputs(options.config, camera, sequence);
      return run_variant_grid_command(options.config, camera, sequence, options.quiet, out, err);
    }
    return options.ablation ? run_ablation_command(options, camera, sequence, out, err)
                            : run_single(options, camera, sequence, out, err);
  } catch (const InvalidArgument& e) {
    err << "hbos-slam: error: " << e.what() << "\n";
    return kSlamBadInput;
  } catch (const std::exception& e) {
    // OpenCV or the standard library failed on something not checked up front.
    err << "hbos-slam: error: " << e.what() << "\n";
    return kSlamOutputError;
  }
}

}  // namespace hbos::slam
