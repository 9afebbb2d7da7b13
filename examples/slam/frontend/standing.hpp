#pragma once
/// \file
/// Where the default screen stands against the best other screen on one row of a results table:
/// the one rule both the variant grid (frontend/grid) and hbos-dynbench report with, so that a
/// row called "tied" in one means what it means in the other.

namespace hbos::slam {

enum class Standing { best, tied, behind };

/// `best` when the default's mean is at most the best other screen's; `tied` when it is above by
/// no more than `spread`, the larger of the two standard deviations over the row's runs (the
/// run-to-run spread issue 7 asks ties to be judged by); otherwise `behind`.
[[nodiscard]] constexpr Standing standing(double default_mean, double best_other_mean,
                                          double spread) noexcept {
  const double gap = default_mean - best_other_mean;
  if (gap <= 0.0) return Standing::best;
  return gap <= spread ? Standing::tied : Standing::behind;
}

/// The standing's word in a report.
[[nodiscard]] constexpr const char* to_string(Standing s) noexcept {
  switch (s) {
    case Standing::best:
      return "best";
    case Standing::tied:
      return "tied";
    case Standing::behind:
      break;
  }
  return "behind";
}

}  // namespace hbos::slam
