#include "dynbench/dynbench_command.hpp"

#include "common/atomic_file.hpp"
#include "common/cli_validators.hpp"
#include "common/stop_on_signal.hpp"
#include "dynbench/bench_figures.hpp"
#include "dynbench/cell_run.hpp"
#include "dynbench/cells.hpp"
#include "dynbench/progress_bar.hpp"
#include "dynbench/screen_comparison.hpp"
#include "dynbench/sequences.hpp"
#include "dynbench/summary.hpp"
#include "frontend/config_options.hpp"

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <hbos/error.hpp>

#include <opencv2/core.hpp>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

namespace hbos::dynbench {

namespace {

namespace fs = std::filesystem;

using hbos::examples::StopOnSignal;

struct CommandOptions {
  BenchSettings settings;
  std::vector<std::uint64_t> seeds;
  bool full = false;
  bool quiet = false;
  std::string cache_dir;
  std::string tracker = "frame";
  std::string rough_pose = "ransac";
};

void add_options(CLI::App& app, CommandOptions& o) {
  BenchSettings& s = o.settings;
  std::string scenarios, variants;
  for (const std::string& n : all_scenarios()) scenarios += (scenarios.empty() ? "" : ", ") + n;
  for (const std::string& n : all_variants()) variants += (variants.empty() ? "" : ", ") + n;
  app.add_option("--scenarios", s.scenarios, "comma-separated scenarios: " + scenarios)
      ->delimiter(',')
      ->capture_default_str()
      ->check(CLI::IsMember(all_scenarios()));
  app.add_option("--variants", s.variants,
                 "comma-separated mask variants: " + variants +
                     " ('' = none: with --every-screen-unmasked, the unmasked cells alone)")
      ->delimiter(',')
      ->capture_default_str()
      ->check(
          [](const std::string& v) {
            const auto& known = all_variants();
            return v.empty() || std::find(known.begin(), known.end(), v) != known.end()
                       ? std::string()
                       : "'" + v + "' is not a mask variant";
          },
          "VARIANT");
  app.add_option("--seeds", o.seeds, "comma-separated seeds (default 1,2)")
      ->delimiter(',')
      ->check(examples::seed_value());
  app.add_option("--frames", s.frames, "frames per sequence (0 = the whole trajectory)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_option("--people", s.people,
                 "people in each rendered scene, 1..3 (default: the scenario's own, 2); the "
                 "sequences are cached apart")
      ->check(CLI::Range(1, 3));
  app.add_option("--screens", s.screens,
                 "comma-separated screens (default: all; none = no screen, i.e. 'mask only' with "
                 "a mask)")
      ->delimiter(',');
  app.add_flag("--every-screen-unmasked", s.every_screen_unmasked,
               "run every selected screen without a mask too (default: only none and default)");
  app.add_flag("--full", o.full,
               "every scenario at full length, every mask variant, seeds 1,2,3 (explicit "
               "--scenarios/--variants/--seeds/--frames still win)");
  app.add_option("--out", s.out_dir, "output folder (dynbench.md, dynbench.json, figures/, cells/)")
      ->capture_default_str()
      ->check(examples::non_empty_path());
  app.add_option("--cache", o.cache_dir, "rendered sequences (default: <out>/cache)")
      ->check(examples::non_empty_path());
  app.add_option("--renderer", s.renderer, "the hbos-render executable")->capture_default_str();
  app.add_flag("--rerender", s.rerender, "render the sequences again even when cached");
  app.add_option("--camera", s.camera, "intrinsics of the rendered sequences")
      ->capture_default_str();
  app.add_option("--tracker", o.tracker, "frame: frame-to-frame odometry; map: local map")
      ->capture_default_str()
      ->check(CLI::IsMember({"frame", "map"}));
  app.add_option("--jobs", s.jobs, "cells run at once (1 for the cleanest timings)")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  slam::add_front_end_options(app, s.base);
  app.add_option("--rough-pose", o.rough_pose, "how the rough pose is found")
      ->capture_default_str()
      ->check(CLI::IsMember({"ransac", "constant-velocity"}));
  app.add_option("--ransac-px", s.base.rough_pose.ransac_threshold_px,
                 "PnP RANSAC inlier threshold [px]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_flag("--quiet", o.quiet, "no progress on stderr");
}

std::string cell_line(const Cell& c, const CellMetrics& m) {
  const auto kept = m.dynamic_kept_share();
  return fmt::format("{} s{} mask {} screen {}: ATE {:.2f} cm, dynamic kept {}", c.scenario, c.seed,
                     c.mask, c.screen, 100.0 * m.ate_rmse_m,
                     kept ? fmt::format("{:.1f} %", 100.0 * *kept) : std::string("n/a"));
}

// Runs task(0), ..., task(n - 1) on `jobs` threads (this one among them), taken in order. The
// first exception stops the rest (as Ctrl-C does) and is rethrown once every thread has ended.
void run_in_parallel(std::size_t n, int jobs, const std::function<void(std::size_t)>& task) {
  std::atomic<std::size_t> next{0};
  std::mutex error_mutex;
  std::exception_ptr first_error;
  const auto worker = [&] {
    for (std::size_t k = next++; k < n && !StopOnSignal::stopped(); k = next++) {
      try {
        task(k);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        StopOnSignal::request();
      }
    }
  };
  std::vector<std::thread> threads;
  const std::size_t threads_wanted = std::min(static_cast<std::size_t>(std::max(jobs, 1)), n);
  for (std::size_t t = 1; t < threads_wanted; ++t) threads.emplace_back(worker);
  worker();
  for (std::thread& t : threads) t.join();
  if (first_error) std::rethrow_exception(first_error);
}

int run_grid(const BenchSettings& settings, std::ostream& out, std::ostream& err, bool quiet) {
  const std::vector<Cell> cells = grid_cells(settings);
  if (cells.empty()) throw InvalidArgument("the grid is empty (no scenario, seed or screen)");
  const bool terminal = &err == &std::cerr && ::isatty(STDERR_FILENO) == 1;
  ProgressBar bar(quiet ? nullptr : &err, terminal, static_cast<int>(cells.size()));
  const StopOnSignal stop_on_signal;

  // 1. The sequences, rendered once (or found in the cache), `jobs` at a time: a renderer spends
  //    half its time encoding PNGs on one core. Then their fingerprints.
  std::vector<std::pair<std::string, std::uint64_t>> to_render;  // scenario, seed; in cell order
  for (const Cell& c : cells) {
    const std::pair<std::string, std::uint64_t> sequence{c.scenario, c.seed};
    if (std::find(to_render.begin(), to_render.end(), sequence) == to_render.end())
      to_render.push_back(sequence);
  }
  std::error_code cache_error;
  fs::create_directories(settings.cache_dir, cache_error);  // once, before the renderers race
  if (cache_error) {
    throw InvalidArgument(
        fmt::format("cannot create cache '{}': {}", settings.cache_dir, cache_error.message()));
  }
  std::vector<std::string> rendered(to_render.size());
  bar.status(fmt::format("rendering {} sequence{} (or taking them from the cache)",
                         to_render.size(), to_render.size() == 1 ? "" : "s"));
  run_in_parallel(to_render.size(), settings.jobs, [&](std::size_t k) {
    rendered[k] = ensure_sequence(settings, to_render[k].first, to_render[k].second);
  });
  std::map<std::string, std::pair<std::string, std::string>> sequences;  // key -> dir, print
  for (std::size_t k = 0; k < to_render.size() && !StopOnSignal::stopped(); ++k) {
    const std::string key = fmt::format("{}_{}", to_render[k].first, to_render[k].second);
    sequences[key] = {rendered[k], sequence_fingerprint(rendered[k])};
  }

  // 2. The cells an earlier run finished with the same settings are taken as they are.
  std::vector<std::optional<CellMetrics>> results(cells.size());
  std::vector<nlohmann::json> expected(cells.size());
  std::vector<std::size_t> to_run;
  for (std::size_t i = 0; i < cells.size() && !StopOnSignal::stopped(); ++i) {
    const auto& [dir, print] = sequences.at(fmt::format("{}_{}", cells[i].scenario, cells[i].seed));
    expected[i] = cell_settings(settings, cells[i], print);
    results[i] = load_finished_cell(settings, cells[i], expected[i]);
    if (results[i]) {
      bar.advance("resumed " + cell_line(cells[i], *results[i]));
    } else {
      to_run.push_back(i);
    }
  }

  // 3. The rest, `jobs` at a time. OpenCV's own threads would only compete with the jobs.
  if (settings.jobs > 1) cv::setNumThreads(1);
  try {
    run_in_parallel(to_run.size(), settings.jobs, [&](std::size_t k) {
      const std::size_t i = to_run[k];
      const Cell& c = cells[i];
      try {
        const auto& dir = sequences.at(fmt::format("{}_{}", c.scenario, c.seed)).first;
        bar.status(
            fmt::format("running {} s{} mask {} screen {}", c.scenario, c.seed, c.mask, c.screen));
        results[i] = run_cell(settings, c, dir, expected[i], StopOnSignal::flag());
        if (results[i]) bar.advance(cell_line(c, *results[i]));
      } catch (const std::exception& e) {
        // Named by its cell, so the failure can be re-run alone; bad input keeps exit status 2.
        const std::string where = fmt::format("cell {} seed {} mask {} screen {}: {}", c.scenario,
                                              c.seed, c.mask, c.screen, e.what());
        if (dynamic_cast<const InvalidArgument*>(&e) != nullptr) throw InvalidArgument(where);
        throw std::runtime_error(where);
      }
    });
  } catch (...) {
    bar.finish();
    throw;
  }
  bar.finish();

  const auto finished = static_cast<std::size_t>(
      std::count_if(results.begin(), results.end(), [](const auto& r) { return r.has_value(); }));
  if (finished < cells.size()) {
    err << fmt::format(
        "hbos-dynbench: interrupted: {} of {} cells finished (kept in {}/cells); run the same "
        "command again to resume\n",
        finished, cells.size(), settings.out_dir);
    return kDynbenchInterrupted;
  }

  // 4. The table, its JSON and the figures.
  std::vector<CellOutcome> outcomes;
  for (std::size_t i = 0; i < cells.size(); ++i) outcomes.push_back({cells[i], *results[i]});
  const std::vector<TableRow> rows = table_rows(outcomes);
  const ScreenComparison comparison = compare_screens(outcomes, rows);
  const std::string md = table_markdown(rows, settings) + comparison_markdown(comparison);
  out << md;
  const fs::path md_path = fs::path(settings.out_dir) / "dynbench.md";
  const fs::path json_path = fs::path(settings.out_dir) / "dynbench.json";
  examples::write_file_atomically(md_path, md);
  nlohmann::json json = table_json(rows, outcomes, settings);
  json["comparison"] = comparison_json(comparison);
  examples::write_file_atomically(json_path, json.dump(1) + "\n");
  out << "wrote " << md_path.string() << "\nwrote " << json_path.string() << "\n";
  for (const std::string& p : write_bench_figures(settings)) out << "wrote " << p << "\n";
  return kDynbenchOk;
}

}  // namespace

int run_dynbench_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  CLI::App app{
      "The dynamic-scene benchmark: renders the scenarios with hbos-render (cached), runs the "
      "front end with every screen on every mask variant and seed, and writes one table "
      "(dynbench.md, dynbench.json) and figures into --out. An interrupted run keeps its "
      "finished cells: the same command resumes it. Exit status: 0 ok, 1 failed, 2 bad input, "
      "130 interrupted.",
      "hbos-dynbench"};
  CommandOptions o;
  o.settings.renderer = built_renderer();
  add_options(app, o);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e, out, err) == 0 ? kDynbenchOk : kDynbenchBadInput;
  }
  BenchSettings& s = o.settings;
  if (o.full) {
    BenchSettings full;
    use_full_grid(full);
    if (app.count("--scenarios") == 0) s.scenarios = full.scenarios;
    if (app.count("--variants") == 0) s.variants = full.variants;
    if (app.count("--frames") == 0) s.frames = full.frames;
    if (app.count("--seeds") == 0) o.seeds = full.seeds;
  }
  s.variants.erase(std::remove(s.variants.begin(), s.variants.end(), std::string()),
                   s.variants.end());
  if (!o.seeds.empty()) s.seeds = o.seeds;
  s.cache_dir = o.cache_dir.empty() ? (fs::path(s.out_dir) / "cache").string() : o.cache_dir;
  s.base.tracker = o.tracker == "map" ? slam::TrackerKind::kMap : slam::TrackerKind::kFrame;
  try {
    s.base.rough_pose.method = slam::parse_rough_pose_method(o.rough_pose);
    return run_grid(s, out, err, o.quiet);
  } catch (const InvalidArgument& e) {
    err << "\nhbos-dynbench: error: " << e.what() << "\n";
    return kDynbenchBadInput;
  } catch (const std::exception& e) {
    err << "\nhbos-dynbench: error: " << e.what() << "\n";
    return kDynbenchFailed;
  }
}

}  // namespace hbos::dynbench
