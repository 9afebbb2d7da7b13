#include "dynbench/summary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

namespace hbos::dynbench {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string cell_text(const Spread& s, int decimals) {
  if (s.n == 0) return "n/a";
  if (s.n == 1) return fmt::format("{:.{}f}", s.mean, decimals);
  return fmt::format("{:.{}f} ± {:.{}f}", s.mean, decimals, s.sd, decimals);
}

nlohmann::json spread_json(const Spread& s) {
  nlohmann::json values = nlohmann::json::array();
  for (const double v : s.values) values.push_back(v);
  return {{"mean", s.n > 0 ? nlohmann::json(s.mean) : nlohmann::json(nullptr)},
          {"sd", s.n > 0 ? nlohmann::json(s.sd) : nlohmann::json(nullptr)},
          {"n", s.n},
          {"values", values}};
}

// "none", "mask only", "mask + chi2", "default alone": what a row ran, in words.
std::string run_label(const std::string& mask, const std::string& screen) {
  if (mask == "none") return screen == "none" ? "none" : screen + " alone";
  return screen == "none" ? "mask only" : "mask + " + screen;
}

/// The front-end settings a run used that differ from the defaults, named in the table's header
/// (empty: none).
std::string non_default_settings(const slam::Config& c) {
  std::string named;
  if (c.tracker == slam::TrackerKind::kMap && !c.screen.provisional_consensus)
    named += ", new points without their own consensus";
  if (c.refinement.huber_from_noise) named += ", Huber width from the matches' noise";
  // Set explicitly, and not to the tracker's own value.
  slam::Config tracker_default = c;
  tracker_default.screen.later_rounds_gate_floor.reset();
  const double later_floor = slam::later_rounds_gate_floor(c);
  if (later_floor != slam::later_rounds_gate_floor(tracker_default)) {
    named += later_floor > 0.0
                 ? fmt::format(", the noise gate's floor {:g} after the first round", later_floor)
                 : std::string(", chi^2's gate floor in every round");
  }
  tracker_default.screen.later_rounds_rigid_field.reset();
  const bool rigid = slam::later_rounds_rigid_field(c);
  if (rigid != slam::later_rounds_rigid_field(tracker_default))
    named += rigid ? ", a rigid field after the first round" : ", an affine field in every round";
  if (c.tracker == slam::TrackerKind::kMap && c.map.local_bundle.enabled)
    named += ", local bundle adjustment";
  return named;
}

}  // namespace

Spread spread_of(const std::vector<double>& values) {
  Spread s;
  for (const double v : values) {
    if (std::isfinite(v)) s.values.push_back(v);
  }
  s.n = static_cast<int>(s.values.size());
  if (s.n == 0) return s;
  for (const double v : s.values) s.mean += v;
  s.mean /= s.n;
  if (s.n > 1) {
    double ss = 0.0;
    for (const double v : s.values) ss += (v - s.mean) * (v - s.mean);
    s.sd = std::sqrt(ss / (s.n - 1));
  }
  return s;
}

std::vector<TableRow> table_rows(const std::vector<CellOutcome>& outcomes) {
  using Key = std::tuple<std::string, std::string, std::string>;
  std::vector<Key> order;
  std::map<Key, std::vector<const CellOutcome*>> groups;
  for (const CellOutcome& o : outcomes) {
    const Key key{o.cell.scenario, o.cell.mask, o.cell.screen};
    if (groups.find(key) == groups.end()) order.push_back(key);
    groups[key].push_back(&o);
  }
  std::vector<TableRow> rows;
  for (const Key& key : order) {
    TableRow r;
    std::tie(r.scenario, r.mask, r.screen) = key;
    std::vector<double> ate, rpe, kept, dropped, tracked, mask, motion, screen;
    for (const CellOutcome* o : groups[key]) {
      const CellMetrics& m = o->metrics;
      r.seeds.push_back(o->cell.seed);
      ate.push_back(100.0 * m.ate_rmse_m);
      rpe.push_back(1000.0 * m.rpe_trans_m);
      const auto share = m.dynamic_kept_share();
      kept.push_back(share ? 100.0 * *share : kNaN);
      dropped.push_back(100.0 * m.static_dropped_share());
      tracked.push_back(100.0 * m.tracked_share());
      mask.push_back(m.mask_ms);
      motion.push_back(m.motion_ms);
      screen.push_back(m.screen_ms);
      r.dynamic_matches += m.dynamic_matches;
    }
    r.ate_cm = spread_of(ate);
    r.rpe_mm = spread_of(rpe);
    r.dynamic_kept_pct = spread_of(kept);
    r.static_dropped_pct = spread_of(dropped);
    r.tracked_pct = spread_of(tracked);
    r.mask_ms = spread_of(mask);
    r.motion_ms = spread_of(motion);
    r.screen_ms = spread_of(screen);
    rows.push_back(std::move(r));
  }
  return rows;
}

std::string table_markdown(const std::vector<TableRow>& rows, const BenchSettings& settings) {
  std::string seeds;
  for (const std::uint64_t s : settings.seeds)
    seeds += (seeds.empty() ? "" : ", ") + fmt::format("{}", s);
  const slam::Config& c = settings.base;
  std::string md = fmt::format(
      "Rendered sequences ({} frames each{}{}), seeds {}; tracker {}, camera {}, rough pose {} ({} "
      "px), {} screening rounds{}. Each cell: mean ± sample standard deviation over the seeds. "
      "Dynamic = a keypoint of the match on a rendered person or carried object (objects/ ids). "
      "Times: per-frame medians [ms], then the mean over seeds.\n\n",
      settings.frames > 0 ? fmt::format("{}", settings.frames) : std::string("all"),
      settings.frames > 0 ? "" : ", whole trajectories",
      settings.people > 0 ? fmt::format(", {} people in each scene", settings.people) : "", seeds,
      slam::to_string(c.tracker), settings.camera, slam::to_string(c.rough_pose.method),
      c.rough_pose.ransac_threshold_px, c.screen.rounds, non_default_settings(c));
  md +=
      "| scenario | mask | screen | ATE RMSE [cm] | RPE [mm/frame] | dynamic matches kept [%] | "
      "static matches dropped [%] | frames tracked [%] | mask [ms] | motion est. [ms] | screen "
      "[ms] |\n"
      "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const TableRow& r : rows) {
    md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", r.scenario,
                      r.mask, r.screen, cell_text(r.ate_cm, 2), cell_text(r.rpe_mm, 2),
                      cell_text(r.dynamic_kept_pct, 1), cell_text(r.static_dropped_pct, 1),
                      cell_text(r.tracked_pct, 1), cell_text(r.mask_ms, 2),
                      cell_text(r.motion_ms, 2), cell_text(r.screen_ms, 3));
  }

  // Table III's form: what each stage costs, per way of running, over every scenario and mask.
  std::vector<std::string> order;
  std::map<std::string, std::vector<const TableRow*>> by_label;
  for (const TableRow& r : rows) {
    const std::string label = run_label(r.mask, r.screen);
    if (by_label.find(label) == by_label.end()) order.push_back(label);
    by_label[label].push_back(&r);
  }
  md +=
      "\nTime per frame by stage, in the form of the HBOS paper's Table III (mean over the rows "
      "above) [ms]:\n\n"
      "| run | segmentation / mask | motion estimation | dynamic point detection and removal | "
      "total |\n"
      "|---|---:|---:|---:|---:|\n";
  for (const std::string& label : order) {
    std::vector<double> mask, motion, screen;
    for (const TableRow* r : by_label[label]) {
      mask.insert(mask.end(), r->mask_ms.values.begin(), r->mask_ms.values.end());
      motion.insert(motion.end(), r->motion_ms.values.begin(), r->motion_ms.values.end());
      screen.insert(screen.end(), r->screen_ms.values.begin(), r->screen_ms.values.end());
    }
    const Spread a = spread_of(mask), b = spread_of(motion), s = spread_of(screen);
    const double total =
        (a.n > 0 ? a.mean : 0.0) + (b.n > 0 ? b.mean : 0.0) + (s.n > 0 ? s.mean : 0.0);
    md += fmt::format("| {} | {:.2f} | {} | {:.3f} | {:.2f} |\n", label, a.mean,
                      b.n > 0 ? fmt::format("{:.2f}", b.mean) : std::string("n/a"), s.mean, total);
  }
  return md;
}

nlohmann::json table_json(const std::vector<TableRow>& rows,
                          const std::vector<CellOutcome>& outcomes, const BenchSettings& settings) {
  nlohmann::json j;
  j["tool"] = "hbos-dynbench";
  j["settings"] = {{"scenarios", settings.scenarios},
                   {"mask_variants", settings.variants},
                   {"seeds", settings.seeds},
                   {"frames", settings.frames},
                   {"people", settings.people > 0 ? nlohmann::json(settings.people)
                                                  : nlohmann::json("the scenario's own")},
                   {"screens", screens_in_order(settings.screens)},
                   {"camera", settings.camera},
                   {"tracker", slam::to_string(settings.base.tracker)},
                   {"rounds", settings.base.screen.rounds},
                   {"huber_from_noise", settings.base.refinement.huber_from_noise},
                   {"local_bundle_adjustment", settings.base.map.local_bundle.enabled},
                   {"provisional_consensus", settings.base.screen.provisional_consensus},
                   {"later_rounds_gate_floor", slam::later_rounds_gate_floor(settings.base)},
                   {"later_rounds_rigid_field", slam::later_rounds_rigid_field(settings.base)},
                   {"rough_pose", slam::to_string(settings.base.rough_pose.method)},
                   {"ransac_threshold_px", settings.base.rough_pose.ransac_threshold_px},
                   {"spread", "sample standard deviation over seeds (n - 1)"},
                   {"times", "per-frame medians in ms, then the mean over seeds"}};
  nlohmann::json out_rows = nlohmann::json::array();
  for (const TableRow& r : rows) {
    out_rows.push_back({{"scenario", r.scenario},
                        {"mask", r.mask},
                        {"screen", r.screen},
                        {"run", run_label(r.mask, r.screen)},
                        {"seeds", r.seeds},
                        {"dynamic_matches", r.dynamic_matches},
                        {"ate_rmse_cm", spread_json(r.ate_cm)},
                        {"rpe_trans_mm_per_frame", spread_json(r.rpe_mm)},
                        {"dynamic_matches_kept_pct", spread_json(r.dynamic_kept_pct)},
                        {"static_matches_dropped_pct", spread_json(r.static_dropped_pct)},
                        {"frames_tracked_pct", spread_json(r.tracked_pct)},
                        {"mask_ms", spread_json(r.mask_ms)},
                        {"motion_estimation_ms", spread_json(r.motion_ms)},
                        {"screen_ms", spread_json(r.screen_ms)}});
  }
  j["rows"] = out_rows;
  nlohmann::json cells = nlohmann::json::array();
  for (const CellOutcome& o : outcomes) {
    cells.push_back({{"id", o.cell.id()}, {"metrics", to_json(o.metrics)}});
  }
  j["cells"] = cells;
  return j;
}

}  // namespace hbos::dynbench
