#include "dynbench/bench_figures.hpp"

#include "dynbench/cell_run.hpp"
#include "frontend/figures.hpp"

#include <fmt/format.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <utility>

namespace hbos::dynbench {

namespace fs = std::filesystem;

namespace {

cv::Mat read_cell_image(const BenchSettings& settings, const Cell& cell, const char* name) {
  const fs::path p = fs::path(cell_dir(settings, cell)) / name;
  return fs::is_regular_file(p) ? cv::imread(p.string(), cv::IMREAD_COLOR) : cv::Mat();
}

// A tile with a caption bar above it, scaled to `width`.
cv::Mat captioned(const cv::Mat& image, const std::string& caption, int width) {
  cv::Mat scaled;
  const double f = static_cast<double>(width) / image.cols;
  cv::resize(image, scaled, cv::Size(width, static_cast<int>(image.rows * f)), 0, 0,
             cv::INTER_AREA);
  constexpr int kBar = 36;
  cv::Mat tile(scaled.rows + kBar, width, CV_8UC3, cv::Scalar(255, 255, 255));
  scaled.copyTo(tile(cv::Rect(0, kBar, width, scaled.rows)));
  cv::putText(tile, caption, {10, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.7, cv::Scalar(30, 30, 30), 2,
              cv::LINE_AA);
  return tile;
}

}  // namespace

std::vector<std::string> write_bench_figures(const BenchSettings& settings) {
  std::vector<std::string> written;
  if (settings.scenarios.empty() || settings.seeds.empty()) return written;
  const std::string& scenario = settings.scenarios.front();
  const std::uint64_t seed = settings.seeds.front();
  const std::string variant = settings.variants.empty() ? "none" : settings.variants.front();
  const fs::path dir = fs::path(settings.out_dir) / "figures";
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) throw std::runtime_error("cannot create '" + dir.string() + "': " + error.message());

  // 1. Trajectories: four ways of running, one top view each, in a 2 x 2 grid.
  const std::vector<std::pair<Cell, std::string>> views = {
      {{scenario, seed, "none", "none"}, "no mask, no screen"},
      {{scenario, seed, "none", "default"}, "no mask, HBOS default screen"},
      {{scenario, seed, variant, "none"}, "mask '" + variant + "' only"},
      {{scenario, seed, variant, "default"}, "mask '" + variant + "' + HBOS default"}};
  std::vector<cv::Mat> tiles;
  for (const auto& [cell, caption] : views) {
    const cv::Mat top = read_cell_image(settings, cell, "top_view.png");
    if (!top.empty())
      tiles.push_back(captioned(top, fmt::format("{} s{}: {}", scenario, seed, caption), 760));
  }
  if (!tiles.empty()) {
    std::vector<cv::Mat> rows;
    for (std::size_t i = 0; i < tiles.size(); i += 2) {
      cv::Mat row = tiles[i];
      if (i + 1 < tiles.size() && tiles[i + 1].rows == row.rows)
        cv::hconcat(row, tiles[i + 1], row);
      if (!rows.empty() && row.cols != rows.front().cols) {
        cv::Mat padded(row.rows, rows.front().cols, CV_8UC3, cv::Scalar(255, 255, 255));
        row.copyTo(padded(cv::Rect(0, 0, std::min(row.cols, padded.cols), row.rows)));
        row = padded;
      }
      rows.push_back(row);
    }
    cv::Mat grid;
    cv::vconcat(rows, grid);
    const std::string path = (dir / "trajectories.png").string();
    slam::write_png(path, grid);
    written.push_back(path);
  }

  // 2. The residual histogram and the matches of one frame, without and with the mask.
  const std::vector<std::pair<Cell, std::string>> singles = {
      {{scenario, seed, "none", "default"}, ""}, {{scenario, seed, variant, "default"}, "_mask"}};
  for (const auto& [cell, suffix] : singles) {
    for (const char* name : {"residual_histogram", "matches"}) {
      const cv::Mat image = read_cell_image(settings, cell, (std::string(name) + ".png").c_str());
      if (image.empty()) continue;
      const std::string path = (dir / (std::string(name) + suffix + ".png")).string();
      slam::write_png(path, image);
      written.push_back(path);
    }
  }
  return written;
}

}  // namespace hbos::dynbench
