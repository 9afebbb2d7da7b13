#include "dynbench/screen_comparison.hpp"

#include "dynbench/paired_statistics.hpp"
#include "frontend/standing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace hbos::dynbench {

namespace {

constexpr const char* kDefault = "default";

using RunKey = std::tuple<std::string, std::string, std::uint64_t>;  // scenario, mask, seed
using AtesByScreen = std::map<std::string, double>;                  // [cm]

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

ScreenRanking rank_group(const std::map<RunKey, AtesByScreen>& runs,
                         const std::vector<std::string>& order, bool masked) {
  ScreenRanking ranking;
  ranking.masked = masked;
  const auto in_group = [&](const RunKey& key) { return (std::get<1>(key) != "none") == masked; };
  if (std::none_of(runs.begin(), runs.end(), [&](const auto& run) { return in_group(run.first); }))
    return ranking;
  // The screens that ran on every run of the group, in the table's order.
  std::vector<std::string> screens;
  for (const std::string& s : order) {
    const bool everywhere = std::all_of(runs.begin(), runs.end(), [&](const auto& run) {
      return !in_group(run.first) || run.second.count(s) > 0;
    });
    if (everywhere) screens.push_back(s);
  }
  if (std::find(screens.begin(), screens.end(), kDefault) == screens.end() || screens.size() < 2)
    return ranking;
  std::vector<double> rank_sum(screens.size(), 0.0);
  std::vector<std::vector<double>> differences(screens.size());
  for (const auto& [key, ates] : runs) {
    if (!in_group(key)) continue;
    std::vector<double> values;
    for (const std::string& s : screens) values.push_back(ates.at(s));
    const std::vector<double> rank = average_ranks(values);
    for (std::size_t i = 0; i < screens.size(); ++i) {
      rank_sum[i] += rank[i];
      differences[i].push_back(ates.at(kDefault) - values[i]);
    }
    ++ranking.runs;
  }
  for (std::size_t i = 0; i < screens.size(); ++i)
    ranking.mean_rank.emplace_back(screens[i], rank_sum[i] / ranking.runs);
  std::stable_sort(ranking.mean_rank.begin(), ranking.mean_rank.end(),
                   [](const auto& a, const auto& b) { return a.second < b.second; });
  for (std::size_t i = 0; i < screens.size(); ++i) {
    if (screens[i] == kDefault) continue;
    PairedAgainst p;
    p.screen = screens[i];
    p.runs = static_cast<int>(differences[i].size());
    for (const double d : differences[i]) {
      p.lower += d < 0.0 ? 1 : 0;
      p.higher += d > 0.0 ? 1 : 0;
    }
    p.equal = p.runs - p.lower - p.higher;
    p.median_difference_cm = median(differences[i]);
    p.wilcoxon_p = wilcoxon_signed_rank(differences[i]).p_value;
    ranking.paired.push_back(p);
  }
  return ranking;
}

std::vector<RowVerdict> row_verdicts(const std::vector<TableRow>& rows) {
  std::vector<RowVerdict> verdicts;
  std::vector<std::pair<std::string, std::string>> groups;
  for (const TableRow& r : rows) {
    const std::pair<std::string, std::string> g{r.scenario, r.mask};
    if (std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
  }
  for (const auto& [scenario, mask] : groups) {
    const TableRow* def = nullptr;
    const TableRow* best = nullptr;
    for (const TableRow& r : rows) {
      if (r.scenario != scenario || r.mask != mask || r.ate_cm.n == 0) continue;
      if (r.screen == kDefault) {
        def = &r;
      } else if (best == nullptr || r.ate_cm.mean < best->ate_cm.mean) {
        best = &r;
      }
    }
    if (def == nullptr || best == nullptr) continue;
    RowVerdict v;
    v.scenario = scenario;
    v.mask = mask;
    v.best_other = best->screen;
    v.best_other_cm = best->ate_cm.mean;
    v.default_cm = def->ate_cm.mean;
    v.spread_cm = std::max(best->ate_cm.sd, def->ate_cm.sd);
    v.verdict =
        hbos::slam::to_string(hbos::slam::standing(v.default_cm, v.best_other_cm, v.spread_cm));
    verdicts.push_back(v);
  }
  return verdicts;
}

std::string p_text(double p) { return std::isnan(p) ? "n/a" : fmt::format("{:.3f}", p); }

}  // namespace

ScreenComparison compare_screens(const std::vector<CellOutcome>& outcomes,
                                 const std::vector<TableRow>& rows) {
  ScreenComparison c;
  std::map<RunKey, AtesByScreen> runs;
  std::vector<std::string> order;  // screens in the cells' order
  for (const CellOutcome& o : outcomes) {
    runs[{o.cell.scenario, o.cell.mask, o.cell.seed}][o.cell.screen] = 100.0 * o.metrics.ate_rmse_m;
    if (std::find(order.begin(), order.end(), o.cell.screen) == order.end())
      order.push_back(o.cell.screen);
    if (100.0 * o.metrics.ate_rmse_m > kFailedRunAteCm)
      c.failed_runs.push_back(
          fmt::format("{}: {:.1f} cm", o.cell.id(), 100.0 * o.metrics.ate_rmse_m));
  }
  for (const bool masked : {true, false}) {
    ScreenRanking r = rank_group(runs, order, masked);
    if (r.runs > 0) c.rankings.push_back(std::move(r));
  }
  c.verdicts = row_verdicts(rows);
  return c;
}

std::string comparison_markdown(const ScreenComparison& c) {
  if (c.rankings.empty() && c.verdicts.empty()) return {};
  std::string failed = "none";
  if (!c.failed_runs.empty()) {
    failed.clear();
    for (const std::string& f : c.failed_runs) failed += (failed.empty() ? "" : "; ") + f;
  }
  std::string md =
      "\nThe default against the other screens, run by run (a run: one scenario, "
      "mask and seed; lower ATE is better):\n";
  for (const ScreenRanking& r : c.rankings) {
    md += fmt::format("\n{}, {} runs. Mean rank by ATE (1 = lowest; ties share their ranks): ",
                      r.masked ? "With a mask" : "Without a mask", r.runs);
    for (std::size_t i = 0; i < r.mean_rank.size(); ++i)
      md += fmt::format("{}{} {:.2f}", i == 0 ? "" : ", ", r.mean_rank[i].first,
                        r.mean_rank[i].second);
    md +=
        ".\n\n| against | default lower | higher | equal | median default - it [cm] | Wilcoxon "
        "p |\n|---|---:|---:|---:|---:|---:|\n";
    for (const PairedAgainst& p : r.paired) {
      md += fmt::format("| {} | {} | {} | {} | {:+.3f} | {} |\n", p.screen, p.lower, p.higher,
                        p.equal, p.median_difference_cm, p_text(p.wilcoxon_p));
    }
  }
  if (!c.verdicts.empty()) {
    md +=
        "\nPer scenario and mask, the default against the screen with the lowest mean ATE (tied: "
        "the gap is within the larger standard deviation over the seeds):\n\n"
        "| scenario | mask | lowest other | its ATE [cm] | default [cm] | spread [cm] | verdict "
        "|\n|---|---|---|---:|---:|---:|---|\n";
    for (const RowVerdict& v : c.verdicts) {
      md += fmt::format("| {} | {} | {} | {:.2f} | {:.2f} | {:.2f} | {} |\n", v.scenario, v.mask,
                        v.best_other, v.best_other_cm, v.default_cm, v.spread_cm, v.verdict);
    }
  }
  md +=
      fmt::format("\nRuns whose ATE exceeds {:g} cm (any screen): {}.\n", kFailedRunAteCm, failed);
  return md;
}

nlohmann::json comparison_json(const ScreenComparison& c) {
  nlohmann::json rankings = nlohmann::json::array();
  for (const ScreenRanking& r : c.rankings) {
    nlohmann::json ranks = nlohmann::json::array();
    for (const auto& [screen, rank] : r.mean_rank)
      ranks.push_back({{"screen", screen}, {"mean_rank", rank}});
    nlohmann::json paired = nlohmann::json::array();
    for (const PairedAgainst& p : r.paired) {
      paired.push_back({{"screen", p.screen},
                        {"runs", p.runs},
                        {"default_lower", p.lower},
                        {"default_higher", p.higher},
                        {"equal", p.equal},
                        {"median_difference_cm", p.median_difference_cm},
                        {"wilcoxon_p", std::isnan(p.wilcoxon_p) ? nlohmann::json(nullptr)
                                                                : nlohmann::json(p.wilcoxon_p)}});
    }
    rankings.push_back({{"masked", r.masked},
                        {"runs", r.runs},
                        {"mean_rank_by_ate", ranks},
                        {"default_against", paired}});
  }
  nlohmann::json verdicts = nlohmann::json::array();
  for (const RowVerdict& v : c.verdicts) {
    verdicts.push_back({{"scenario", v.scenario},
                        {"mask", v.mask},
                        {"lowest_other", v.best_other},
                        {"lowest_other_ate_cm", v.best_other_cm},
                        {"default_ate_cm", v.default_cm},
                        {"spread_cm", v.spread_cm},
                        {"verdict", v.verdict}});
  }
  return {{"rankings", rankings},
          {"verdicts", verdicts},
          {"failed_run_ate_cm", kFailedRunAteCm},
          {"failed_runs", c.failed_runs}};
}

}  // namespace hbos::dynbench
