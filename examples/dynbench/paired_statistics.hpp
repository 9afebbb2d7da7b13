#pragma once
/// \file
/// Rank statistics for comparing screens run by run: average ranks (ties share the mean of the
/// ranks they span) and the Wilcoxon signed-rank test on paired differences. The test follows
/// scipy.stats.wilcoxon's defaults (SciPy 1.10: two-sided, zero differences dropped, no
/// continuity correction, the exact null distribution for at most 50 differences without a
/// zero, else the normal approximation with the tie correction), so its p-values can be checked
/// against SciPy's.

#include <vector>

namespace hbos::dynbench {

/// The rank of each value among `values` (1 = smallest); tied values share the mean of the ranks
/// they span. NaN values are not expected (the caller leaves them out).
[[nodiscard]] std::vector<double> average_ranks(const std::vector<double>& values);

struct SignedRankTest {
  int n = 0;  ///< differences entering the test (nonzero ones in the normal approximation)
  double statistic = 0.0;  ///< min(sum of ranks of the positive, of the negative differences)
  double p_value = 0.0;    ///< two-sided; NaN when there is no nonzero difference
  bool exact = false;      ///< the exact null distribution (else the normal approximation)
};

/// The two-sided Wilcoxon signed-rank test of "the differences are symmetric about 0".
[[nodiscard]] SignedRankTest wilcoxon_signed_rank(const std::vector<double>& differences);

}  // namespace hbos::dynbench
