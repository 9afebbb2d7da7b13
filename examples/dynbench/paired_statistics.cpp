#include "dynbench/paired_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>

namespace hbos::dynbench {

namespace {

constexpr std::size_t kMaxExact = 50;  // SciPy's "auto": exact up to 50 differences

// The null distribution of the positive rank sum for n differences: P(T+ = k) for k = 0 ..
// n(n+1)/2, from the number of subsets of {1, ..., n} with sum k. Counts stay below 2^50, so
// doubles hold them exactly.
std::vector<double> signed_rank_distribution(std::size_t n) {
  const std::size_t top = n * (n + 1) / 2;
  std::vector<double> count(top + 1, 0.0);
  count[0] = 1.0;
  for (std::size_t rank = 1; rank <= n; ++rank) {
    for (std::size_t k = rank * (rank + 1) / 2; k >= rank; --k) count[k] += count[k - rank];
  }
  const double total = std::ldexp(1.0, static_cast<int>(n));
  for (double& c : count) c /= total;
  return count;
}

}  // namespace

std::vector<double> average_ranks(const std::vector<double>& values) {
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  std::vector<double> rank(values.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i + 1;
    while (j < order.size() && values[order[j]] == values[order[i]]) ++j;
    // Positions i .. j-1 hold equal values: ranks i+1 .. j, whose mean is (i + 1 + j) / 2.
    const double shared = 0.5 * static_cast<double>(i + 1 + j);
    for (std::size_t k = i; k < j; ++k) rank[order[k]] = shared;
    i = j;
  }
  return rank;
}

SignedRankTest wilcoxon_signed_rank(const std::vector<double>& differences) {
  SignedRankTest t;
  t.p_value = std::numeric_limits<double>::quiet_NaN();
  const bool has_zero =
      std::any_of(differences.begin(), differences.end(), [](double d) { return d == 0.0; });
  t.exact = differences.size() <= kMaxExact && !has_zero;
  std::vector<double> d;
  for (const double x : differences) {
    if (x != 0.0) d.push_back(x);
  }
  if (d.empty()) return t;
  std::vector<double> magnitude(d.size());
  std::transform(d.begin(), d.end(), magnitude.begin(), [](double x) { return std::abs(x); });
  const std::vector<double> rank = average_ranks(magnitude);
  double plus = 0.0, minus = 0.0;
  for (std::size_t i = 0; i < d.size(); ++i) (d[i] > 0.0 ? plus : minus) += rank[i];
  t.n = static_cast<int>(d.size());
  t.statistic = std::min(plus, minus);
  const auto n = static_cast<double>(d.size());

  if (t.exact) {
    const std::vector<double> pmf = signed_rank_distribution(d.size());
    // As SciPy: the positive rank sum, truncated to an integer (exact only without ties).
    const auto r = static_cast<std::size_t>(plus);
    if (r == (pmf.size() - 1) / 2) {
      t.p_value = 1.0;
    } else {
      const double less = std::accumulate(pmf.begin(), pmf.begin() + static_cast<long>(r) + 1, 0.0);
      const double greater = std::accumulate(pmf.begin() + static_cast<long>(r), pmf.end(), 0.0);
      t.p_value = std::clamp(2.0 * std::min(less, greater), 0.0, 1.0);
    }
    return t;
  }
  // The normal approximation: mean n(n+1)/4, variance n(n+1)(2n+1)/24 less the ties' share.
  double variance = n * (n + 1.0) * (2.0 * n + 1.0);
  std::vector<double> sorted = rank;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < sorted.size();) {
    std::size_t j = i + 1;
    while (j < sorted.size() && sorted[j] == sorted[i]) ++j;
    const auto tied = static_cast<double>(j - i);
    if (j - i > 1) variance -= 0.5 * tied * (tied * tied - 1.0);
    i = j;
  }
  const double se = std::sqrt(variance / 24.0);
  const double z = (t.statistic - n * (n + 1.0) * 0.25) / se;
  t.p_value = std::erfc(std::abs(z) / std::sqrt(2.0));  // 2 * (1 - Phi(|z|))
  return t;
}

}  // namespace hbos::dynbench
