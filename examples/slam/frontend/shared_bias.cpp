#include "frontend/shared_bias.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <unordered_map>

namespace hbos::slam {

namespace {

struct Cell {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int count = 0;
};

/// The median of |m|^2 / (s^2 (b2 + 1/n)) over the cells; `ratio` is scratch.
double median_statistic(const std::vector<double>& mean_sq, const std::vector<double>& inv_n,
                        double b2, std::vector<double>& ratio) {
  ratio.resize(mean_sq.size());
  for (std::size_t c = 0; c < mean_sq.size(); ++c) ratio[c] = mean_sq[c] / (b2 + inv_n[c]);
  const auto mid = ratio.begin() + static_cast<std::ptrdiff_t>(ratio.size() / 2);
  std::nth_element(ratio.begin(), mid, ratio.end());
  if (ratio.size() % 2 == 1) return *mid;
  return 0.5 * (*mid + *std::max_element(ratio.begin(), mid));
}

}  // namespace

double shared_bias_scales(const std::vector<Eigen::Vector2d>& pixel,
                          const std::vector<Eigen::Vector2d>& residual, double noise,
                          double cell_px, int min_matches, int min_cells) {
  if (pixel.size() != residual.size())
    throw InvalidArgument(
        fmt::format("shared bias: {} pixels for {} residuals", pixel.size(), residual.size()));
  if (!(std::isfinite(noise) && noise > 0.0) || !(std::isfinite(cell_px) && cell_px > 0.0))
    throw InvalidArgument(fmt::format(
        "shared bias: noise scale {} and cell size {} px must be finite and > 0", noise, cell_px));

  std::unordered_map<std::int64_t, Cell> cells;
  for (std::size_t i = 0; i < pixel.size(); ++i) {
    if (!pixel[i].allFinite() || !residual[i].allFinite()) continue;
    const auto cx = static_cast<std::int64_t>(std::floor(pixel[i].x() / cell_px));
    const auto cy = static_cast<std::int64_t>(std::floor(pixel[i].y() / cell_px));
    Cell& cell = cells[cx * (std::int64_t{1} << 32) + cy];
    cell.sum += residual[i];
    ++cell.count;
  }
  // In noise-scale units: |m|^2 / s^2 and 1 / n per usable cell.
  std::vector<double> mean_sq, inv_n;
  for (const auto& [key, cell] : cells) {
    if (cell.count < min_matches) continue;
    const Eigen::Vector2d mean = cell.sum / cell.count;
    mean_sq.push_back(mean.squaredNorm() / (noise * noise));
    inv_n.push_back(1.0 / cell.count);
  }
  if (static_cast<int>(mean_sq.size()) < std::max(min_cells, 1)) return 0.0;

  const double target = 2.0 * std::log(2.0);  // the median of chi-square with 2 dof
  std::vector<double> ratio;
  if (median_statistic(mean_sq, inv_n, 0.0, ratio) <= target) return 0.0;
  // The median falls as b^2 grows: bracket, then bisect.
  double lo = 0.0, hi = 1.0;
  while (median_statistic(mean_sq, inv_n, hi, ratio) > target && hi < 1e12) hi *= 4.0;
  for (int step = 0; step < 100 && hi - lo > 1e-12 * hi; ++step) {
    const double mid = 0.5 * (lo + hi);
    (median_statistic(mean_sq, inv_n, mid, ratio) > target ? lo : hi) = mid;
  }
  return std::sqrt(0.5 * (lo + hi));
}

}  // namespace hbos::slam
