/// \file
/// hbos-render: renders a dynamic-scene RGB-D sequence (a TUM-format folder with ground truth,
/// object ids and segmentation-mask variants) on a real fr3 camera path. See docs/renderer.md.

#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "common/cli_validators.hpp"
#include "common/stop_on_signal.hpp"
#include "render/sequence.hpp"
#include "render/writer.hpp"

namespace {

void draw_progress(int done, int total, double seconds) {
  constexpr int kWidth = 30;
  const int filled = total > 0 ? done * kWidth / total : kWidth;
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(kWidth, ' ');
  const double fps = seconds > 0 ? done / seconds : 0.0;
  std::fprintf(stderr, "\r[%s] %d/%d frames  %.1f fps", bar.c_str(), done, total, fps);
  if (done == total) std::fputc('\n', stderr);
  std::fflush(stderr);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace hbos::render;
  CLI::App app{
      "hbos-render: a seeded, deterministic RGB-D sequence of people in a room, seen "
      "along a real TUM fr3 camera path (OSMesa), with per-pixel ground truth"};
  SequenceOptions o;
  std::string out;
  bool overwrite = false;
  bool quiet = false;
  std::string names;
  for (const auto& n : scenario_names()) names += (names.empty() ? "" : ", ") + n;
  app.add_option("--scenario", o.scenario, "scenario: " + names)->capture_default_str();
  app.add_option("--seed", o.seed, "seed (same scenario + seed = same bytes)")
      ->check(hbos::examples::seed_value())
      ->capture_default_str();
  app.add_option("--out", out,
                 "output folder (TUM format; written via <out>.tmp; Ctrl-C leaves neither)")
      ->required();
  app.add_option("--frames", o.frames, "frames to render (0 = the whole trajectory)")
      ->capture_default_str();
  app.add_option("--people", o.people, "people in the scene, 1..3 (default: the scenario's)")
      ->check(CLI::Range(1, 3));
  std::string data_dir = o.data_dir.string();
  app.add_option("--data-dir", data_dir, "renderer data (textures/, trajectories/)")
      ->capture_default_str();
  app.add_flag("--overwrite", overwrite, "replace an existing output folder");
  app.add_flag("--quiet", quiet, "no progress bar");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  o.data_dir = data_dir;
  try {
    SequenceRenderer renderer(o);
    const bool bar = !quiet && isatty(fileno(stderr));
    const auto start = std::chrono::steady_clock::now();
    Progress progress;
    if (bar) {
      progress = [&](int done, int total) {
        if (done % 5 == 0 || done == total) {
          draw_progress(
              done, total,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        }
      };
    }
    const hbos::examples::StopOnSignal stop_on_signal;
    const WriteStats s =
        write_sequence(renderer, out, overwrite, progress, hbos::examples::StopOnSignal::flag());
    std::printf("hbos-render: %s seed %llu: %d frames, %zu people -> %s\n", o.scenario.c_str(),
                static_cast<unsigned long long>(o.seed), s.frames,
                renderer.scenario().people.size(), out.c_str());
    std::printf("hbos-render: %.1f s, %.1f frames/s (render + sensor model %.1f frames/s)\n",
                s.seconds, s.frames / s.seconds, s.frames / s.render_seconds);
    return 0;
  } catch (const Interrupted& e) {
    if (!quiet && isatty(fileno(stderr))) std::fputc('\n', stderr);  // below the progress bar
    std::cerr << "hbos-render: " << e.what() << "\n";
    return 130;
  } catch (const UsageError& e) {
    std::cerr << "hbos-render: error: " << e.what() << "\n";
    return 2;
  } catch (const InputError& e) {
    std::cerr << "hbos-render: error: " << e.what() << "\n";
    return 2;
  } catch (const OutputError& e) {
    std::cerr << "hbos-render: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "hbos-render: error: " << e.what() << "\n";
    return 1;
  }
}
