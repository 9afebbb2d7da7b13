#include "frontend/keypoint_spread.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>

namespace hbos::slam {

std::vector<cv::KeyPoint> spread_keypoints(const std::vector<cv::KeyPoint>& pool, int target,
                                           float cell_px) {
  if (target <= 0) return {};
  if (static_cast<std::size_t>(target) >= pool.size()) return pool;
  std::map<int, std::vector<std::size_t>> by_level;
  for (std::size_t i = 0; i < pool.size(); ++i) by_level[pool[i].octave].push_back(i);

  // Each level's quota: its share of the pool, by largest remainder so they sum to `target`.
  std::vector<std::pair<int, std::size_t>> quota;         // level, keypoints to keep
  std::vector<std::pair<double, std::size_t>> remainder;  // fraction, index into `quota`
  std::size_t given = 0;
  for (const auto& [level, members] : by_level) {
    const double share = static_cast<double>(target) * static_cast<double>(members.size()) /
                         static_cast<double>(pool.size());
    remainder.emplace_back(share - std::floor(share), quota.size());
    quota.emplace_back(level, static_cast<std::size_t>(std::floor(share)));
    given += quota.back().second;
  }
  std::stable_sort(remainder.begin(), remainder.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t k = 0; given < static_cast<std::size_t>(target) && k < remainder.size(); ++k) {
    ++quota[remainder[k].second].second;
    ++given;
  }

  std::vector<std::uint8_t> keep(pool.size(), 0);
  for (const auto& [level, count] : quota) {
    std::vector<std::size_t>& members = by_level[level];
    // Strongest first within each cell, then by the round: (rank in cell, -response).
    std::stable_sort(members.begin(), members.end(), [&](std::size_t a, std::size_t b) {
      return pool[a].response > pool[b].response;
    });
    std::map<std::pair<int, int>, int> taken_in_cell;
    std::vector<std::pair<int, std::size_t>> ranked;  // rank in its cell, pool index
    for (const std::size_t i : members) {
      const std::pair<int, int> cell{static_cast<int>(std::floor(pool[i].pt.x / cell_px)),
                                     static_cast<int>(std::floor(pool[i].pt.y / cell_px))};
      ranked.emplace_back(taken_in_cell[cell]++, i);
    }
    // Stable: within a round, the strongest first (the order above).
    std::stable_sort(ranked.begin(), ranked.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t k = 0; k < count && k < ranked.size(); ++k) keep[ranked[k].second] = 1;
  }
  std::vector<cv::KeyPoint> out;
  out.reserve(static_cast<std::size_t>(target));
  for (std::size_t i = 0; i < pool.size(); ++i) {
    if (keep[i] != 0) out.push_back(pool[i]);
  }
  return out;
}

}  // namespace hbos::slam
