// The benchmark's run-by-run comparison of the screens (dynbench/screen_comparison.hpp) and the
// rank statistics under it (dynbench/paired_statistics.hpp). The p-values and ranks are
// SciPy 1.10.1's (scipy.stats.wilcoxon with its defaults, scipy.stats.rankdata), printed with
// repr() on the development machine:
//   wilcoxon([0.5, -1.2, 2.3, 0.7, 1.1, -0.3, 0.9, 1.6]) -> 7.0, 0.1484375
//   wilcoxon([1, -1, 2, 3, -2, 4, 5]) -> 5.0, 0.15625
//   wilcoxon([0.0, 1.5, -0.4, 2.2, 0.9, 1.3, -0.2, 0.8]) -> 3.0, 0.06297905121445523
//   wilcoxon([(i % 7) - 2.5 + 0.01 * i for i in range(60)]) -> 599.0, 0.02000433540910699
//   wilcoxon([1, -1]) -> 1.5, 1.0
//   wilcoxon([0, 1, 1, -1, 2, 2, -2, 3, 3, 3, -4]) -> 17.0, 0.28072258109188986
//   rankdata([3, 1, 2, 2]) -> [4, 1, 2.5, 2.5]

#include <catch2/catch.hpp>

#include "dynbench/paired_statistics.hpp"
#include "dynbench/screen_comparison.hpp"

#include <cmath>
#include <string>
#include <vector>

using hbos::dynbench::average_ranks;
using hbos::dynbench::CellOutcome;
using hbos::dynbench::compare_screens;
using hbos::dynbench::ScreenComparison;
using hbos::dynbench::wilcoxon_signed_rank;

namespace {

void check_against_scipy(const std::vector<double>& d, double statistic, double p, bool exact) {
  const auto t = wilcoxon_signed_rank(d);
  CHECK(t.statistic == statistic);
  CHECK(t.p_value == Approx(p).epsilon(1e-12));
  CHECK(t.exact == exact);
}

CellOutcome outcome(const std::string& scenario, const std::string& mask, std::uint64_t seed,
                    const std::string& screen, double ate_cm) {
  CellOutcome o;
  o.cell.scenario = scenario;
  o.cell.mask = mask;
  o.cell.seed = seed;
  o.cell.screen = screen;
  o.metrics.ate_rmse_m = ate_cm / 100.0;
  o.metrics.frames = o.metrics.frames_tracked = 300;
  return o;
}

}  // namespace

TEST_CASE("paired statistics: SciPy's ranks and Wilcoxon p-values", "[dynbench][statistics]") {
  CHECK(average_ranks({3, 1, 2, 2}) == std::vector<double>{4, 1, 2.5, 2.5});
  CHECK(average_ranks({}).empty());
  check_against_scipy({0.5, -1.2, 2.3, 0.7, 1.1, -0.3, 0.9, 1.6}, 7.0, 0.1484375, true);
  check_against_scipy({1, -1, 2, 3, -2, 4, 5}, 5.0, 0.15625, true);
  check_against_scipy({0.0, 1.5, -0.4, 2.2, 0.9, 1.3, -0.2, 0.8}, 3.0, 0.06297905121445523, false);
  std::vector<double> sixty;
  for (int i = 0; i < 60; ++i) sixty.push_back((i % 7) - 2.5 + 0.01 * i);
  check_against_scipy(sixty, 599.0, 0.02000433540910699, false);
  check_against_scipy({1, -1}, 1.5, 1.0, true);
  check_against_scipy({0, 1, 1, -1, 2, 2, -2, 3, 3, 3, -4}, 17.0, 0.28072258109188986, false);
  // Nothing differs: no test.
  CHECK(std::isnan(wilcoxon_signed_rank({0.0, 0.0}).p_value));
  CHECK(std::isnan(wilcoxon_signed_rank({}).p_value));
}

TEST_CASE("paired statistics: properties of the signed-rank test", "[dynbench][statistics]") {
  // Mirroring every difference leaves a two-sided test unchanged; scaling them too.
  const std::vector<double> d{0.3, -1.1, 2.5, 0.2, 1.4, -0.6, 0.8, 1.9, 2.2, -0.1};
  std::vector<double> mirrored, scaled;
  for (const double x : d) {
    mirrored.push_back(-x);
    scaled.push_back(7.5 * x);
  }
  const double p = wilcoxon_signed_rank(d).p_value;
  CHECK(wilcoxon_signed_rank(mirrored).p_value == Approx(p).epsilon(1e-14));
  CHECK(wilcoxon_signed_rank(scaled).p_value == p);
  // All of one sign: the smallest p the exact test gives for n, 2 / 2^n.
  CHECK(wilcoxon_signed_rank({1, 2, 3, 4, 5, 6}).p_value == Approx(2.0 / 64.0).epsilon(1e-15));
}

TEST_CASE("screen comparison: ranks, pairs and verdicts over runs", "[dynbench][statistics]") {
  // Two scenarios x two seeds with a mask, the same without one. With the mask the default is
  // lowest on three runs and second on one; without it chi2 ran too and was always lower.
  std::vector<CellOutcome> outcomes;
  const auto add = [&](const char* scenario, const char* mask, std::uint64_t seed, double def,
                       double chi2, double quantile) {
    outcomes.push_back(outcome(scenario, mask, seed, "default", def));
    outcomes.push_back(outcome(scenario, mask, seed, "chi2", chi2));
    if (quantile > 0.0) outcomes.push_back(outcome(scenario, mask, seed, "quantile", quantile));
  };
  add("a", "eroded", 1, 1.0, 2.0, 3.0);
  add("a", "eroded", 2, 1.0, 1.5, 0.5);
  add("b", "eroded", 1, 0.4, 0.6, 0.8);
  add("b", "eroded", 2, 0.4, 0.4, 0.9);  // a tie with chi2
  add("a", "none", 1, 3.0, 2.0, 0.0);
  add("a", "none", 2, 3.0, 2.5, 0.0);
  const ScreenComparison c = compare_screens(outcomes, hbos::dynbench::table_rows(outcomes));

  REQUIRE(c.rankings.size() == 2);
  const auto& masked = c.rankings[0];
  CHECK(masked.masked);
  CHECK(masked.runs == 4);
  // Ranks: default 1, 2, 1, 1.5; chi2 2, 3, 2, 1.5; quantile 3, 1, 3, 3.
  REQUIRE(masked.mean_rank.size() == 3);
  CHECK(masked.mean_rank[0].first == "default");
  CHECK(masked.mean_rank[0].second == Approx(5.5 / 4));
  CHECK(masked.mean_rank[1].first == "chi2");
  CHECK(masked.mean_rank[1].second == Approx(8.5 / 4));
  CHECK(masked.mean_rank[2].first == "quantile");
  CHECK(masked.mean_rank[2].second == Approx(10.0 / 4));
  double rank_total = 0.0;
  for (const auto& r : masked.mean_rank) rank_total += r.second;
  CHECK(rank_total == Approx(6.0));  // 1 + 2 + 3 on every run
  REQUIRE(masked.paired.size() == 2);
  CHECK(masked.paired[0].screen == "chi2");
  CHECK(masked.paired[0].lower == 3);
  CHECK(masked.paired[0].higher == 0);
  CHECK(masked.paired[0].equal == 1);
  CHECK(masked.paired[0].median_difference_cm == Approx(-0.35));
  CHECK(masked.paired[1].screen == "quantile");
  CHECK(masked.paired[1].lower == 3);
  CHECK(masked.paired[1].higher == 1);

  const auto& unmasked = c.rankings[1];
  CHECK_FALSE(unmasked.masked);
  CHECK(unmasked.runs == 2);
  CHECK(unmasked.mean_rank[0].first == "chi2");
  CHECK(unmasked.paired.size() == 1);  // the quantile gate did not run without a mask
  CHECK(unmasked.paired[0].higher == 2);

  // Verdicts: a/eroded: default 1.0 +- 0, quantile 1.75 +- 1.77, chi2 1.75: best.
  // a/none: default 3.0 +- 0 against chi2 2.25 +- 0.35: behind. b/eroded: best.
  REQUIRE(c.verdicts.size() == 3);
  CHECK(c.verdicts[0].verdict == "best");
  CHECK(c.verdicts[1].scenario == "b");
  CHECK(c.verdicts[1].verdict == "best");
  CHECK(c.verdicts[2].mask == "none");
  CHECK(c.verdicts[2].best_other == "chi2");
  CHECK(c.verdicts[2].verdict == "behind");
  CHECK(c.failed_runs.empty());
  CHECK_THAT(
      hbos::dynbench::comparison_markdown(c),
      Catch::Contains("With a mask, 4 runs") && Catch::Contains("exceeds 5 cm (any screen): none"));

  // Within the spread: tied.
  std::vector<CellOutcome> close;
  close.push_back(outcome("a", "eroded", 1, "default", 1.0));
  close.push_back(outcome("a", "eroded", 2, "default", 2.0));
  close.push_back(outcome("a", "eroded", 1, "mad", 1.2));
  close.push_back(outcome("a", "eroded", 2, "mad", 1.4));
  close.push_back(outcome("a", "eroded", 3, "default", 1.5));
  close.push_back(outcome("a", "eroded", 3, "mad", 49.5));  // lost the room
  const ScreenComparison tied = compare_screens(close, hbos::dynbench::table_rows(close));
  REQUIRE(tied.verdicts.size() == 1);
  CHECK(tied.verdicts[0].verdict == "best");  // the failed run puts mad's mean at 17.4
  REQUIRE(tied.failed_runs.size() == 1);
  CHECK(tied.failed_runs[0] == "a_s3_eroded_mad: 49.5 cm");
  close.pop_back();
  close.pop_back();
  const ScreenComparison within = compare_screens(close, hbos::dynbench::table_rows(close));
  CHECK(within.verdicts[0].verdict == "tied");  // gap 0.2, spread 0.71

  // Without the default there is nothing to compare.
  std::vector<CellOutcome> baselines{outcome("a", "eroded", 1, "chi2", 1.0),
                                     outcome("a", "eroded", 1, "mad", 2.0)};
  const ScreenComparison none = compare_screens(baselines, hbos::dynbench::table_rows(baselines));
  CHECK(none.rankings.empty());
  CHECK(none.verdicts.empty());
  CHECK(hbos::dynbench::comparison_markdown(none).empty());
}
