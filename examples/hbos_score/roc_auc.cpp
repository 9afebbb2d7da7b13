#include "roc_auc.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace hbos::cli {

std::optional<double> roc_auc(const Eigen::Ref<const Eigen::VectorXd>& scores,
                              const Eigen::Ref<const Eigen::VectorXi>& labels) {
  if (scores.size() != labels.size()) {
    throw std::invalid_argument("roc_auc: " + std::to_string(scores.size()) + " scores but " +
                                std::to_string(labels.size()) + " labels");
  }
  const auto n = static_cast<std::size_t>(scores.size());
  std::uint64_t n_pos = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    if (labels[k] != 0 && labels[k] != 1) {
      throw std::invalid_argument("roc_auc: label " + std::to_string(i) + " is " +
                                  std::to_string(labels[k]) + ", not 0 or 1");
    }
    if (std::isnan(scores[k]))
      throw std::invalid_argument("roc_auc: score " + std::to_string(i) + " is NaN");
    n_pos += static_cast<std::uint64_t>(labels[k]);
  }
  const std::uint64_t n_neg = n - n_pos;
  if (n_pos == 0 || n_neg == 0) return std::nullopt;

  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return scores[static_cast<Eigen::Index>(a)] < scores[static_cast<Eigen::Index>(b)];
  });

  // Ranks are 1-based; a run of ties at sorted positions [first, last] shares the rank
  // (first + last) / 2 + 1, so twice it, first + last + 2, is an integer.
  std::uint64_t twice_rank_sum = 0;
  for (std::size_t first = 0; first < n;) {
    std::size_t last = first;
    const double value = scores[static_cast<Eigen::Index>(order[first])];
    std::uint64_t positives = 0;
    while (true) {
      positives += static_cast<std::uint64_t>(labels[static_cast<Eigen::Index>(order[last])]);
      if (last + 1 == n || scores[static_cast<Eigen::Index>(order[last + 1])] != value) break;
      ++last;
    }
    twice_rank_sum += positives * (first + last + 2);
    first = last + 1;
  }
  // 2 U = 2 R_1 - n_1 (n_1 + 1) <= 2 n_1 n_0 <= n^2 / 2: exact in a double for n < 2^27.
  const std::uint64_t twice_u = twice_rank_sum - n_pos * (n_pos + 1);
  return static_cast<double>(twice_u) /
         (2.0 * static_cast<double>(n_pos) * static_cast<double>(n_neg));
}

}  // namespace hbos::cli
