#include "frontend/grid/grid_report.hpp"

#include "frontend/grid/parallax.hpp"
#include "frontend/grid/run_cache.hpp"
#include "frontend/standing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace hbos::slam {

namespace {

Spread grid_spread_of(const std::vector<double>& values) {
  Spread s;
  double sum = 0.0;
  for (const double v : values) {
    if (!std::isfinite(v)) continue;
    sum += v;
    ++s.n;
  }
  if (s.n == 0) return {std::nan(""), std::nan(""), 0};
  s.mean = sum / s.n;
  double squares = 0.0;
  for (const double v : values) {
    if (std::isfinite(v)) squares += (v - s.mean) * (v - s.mean);
  }
  s.sd = s.n > 1 ? std::sqrt(squares / (s.n - 1)) : 0.0;
  return s;
}

const std::vector<double>* grid_parallax_of(const GridResult& grid, const std::string& variant) {
  for (const GridVariant& v : grid.variants) {
    if (v.variant.name == variant) return &v.parallax_px;
  }
  return nullptr;
}

bool grid_hidden(const std::vector<double>* parallax, std::size_t frame) {
  return parallax != nullptr && frame < parallax->size() && (*parallax)[frame] < kHiddenParallaxPx;
}

/// Per variant, in grid order: the metric of `mask` x `screen` (NaN when missing).
std::vector<double> grid_per_variant(const GridResult& grid, const std::string& mask,
                                     const std::string& screen, bool ate) {
  std::vector<double> values;
  for (const GridVariant& v : grid.variants) {
    double value = std::nan("");
    for (const GridRun& r : grid.runs) {
      if (r.variant == v.variant.name && r.mask == mask && r.screen == screen) {
        value = ate ? 100.0 * r.ate_rmse_m : 1000.0 * r.rpe_trans_rmse_m;
      }
    }
    values.push_back(value);
  }
  return values;
}

std::string grid_pm(const Spread& s) {
  return s.n == 0 ? std::string("n/a") : fmt::format("{:.2f} ± {:.2f}", s.mean, s.sd);
}

std::string grid_share(long part, long whole) {
  return whole == 0
             ? std::string("n/a (0)")
             : fmt::format("{:.1f} of {}",
                           100.0 * static_cast<double>(part) / static_cast<double>(whole), whole);
}

nlohmann::json grid_spread_json(const Spread& s) {
  if (s.n == 0) return nullptr;
  return {{"mean", s.mean}, {"sd", s.sd}, {"n", s.n}};
}

}  // namespace

std::vector<GridCell> grid_cells(const GridResult& grid) {
  std::vector<GridCell> cells;
  for (const std::string& mask : grid.masks) {
    for (const std::string& screen : grid.screens) {
      GridCell c;
      c.mask = mask;
      c.screen = screen;
      c.ate_cm = grid_spread_of(grid_per_variant(grid, mask, screen, true));
      c.rpe_mm = grid_spread_of(grid_per_variant(grid, mask, screen, false));
      for (const GridRun& r : grid.runs) {
        if (r.mask != mask || r.screen != screen) continue;
        c.person_matches += r.person_matches;
        c.person_survivors += r.person_survivors;
        c.static_matches += r.static_matches;
        c.static_dropped += r.static_dropped;
        const std::vector<double>* parallax = grid_parallax_of(grid, r.variant);
        for (std::size_t i = 1; i < r.frame_person_matches.size(); ++i) {
          const bool h = grid_hidden(parallax, i);
          (h ? c.hidden_matches : c.other_matches) += r.frame_person_matches[i];
          (h ? c.hidden_survivors : c.other_survivors) += r.frame_person_survivors[i];
        }
      }
      cells.push_back(c);
    }
  }
  return cells;
}

std::vector<GridVerdict> grid_verdicts(const GridResult& grid, const std::vector<GridCell>& cells) {
  std::vector<GridVerdict> verdicts;
  for (const std::string& mask : grid.masks) {
    for (const bool ate : {true, false}) {
      // The best screen other than the default, and the default.
      const GridCell* best = nullptr;
      const GridCell* def = nullptr;
      for (const GridCell& c : cells) {
        if (c.mask != mask) continue;
        const Spread& s = ate ? c.ate_cm : c.rpe_mm;
        if (s.n == 0) continue;
        if (c.screen == "default") {
          def = &c;
        } else if (best == nullptr || s.mean < (ate ? best->ate_cm : best->rpe_mm).mean) {
          best = &c;
        }
      }
      if (best == nullptr || def == nullptr) continue;
      const Spread& b = ate ? best->ate_cm : best->rpe_mm;
      const Spread& d = ate ? def->ate_cm : def->rpe_mm;
      GridVerdict v;
      v.mask = mask;
      v.metric = ate ? "ATE" : "RPE";
      v.best_screen = best->screen;
      v.best_mean = b.mean;
      v.default_mean = d.mean;
      v.spread = std::max(b.sd, d.sd);
      v.verdict = to_string(standing(d.mean, b.mean, v.spread));
      const std::vector<double> dv = grid_per_variant(grid, mask, "default", ate);
      const std::vector<double> bv = grid_per_variant(grid, mask, best->screen, ate);
      std::vector<double> gaps;
      for (std::size_t i = 0; i < dv.size(); ++i) {
        gaps.push_back(dv[i] - bv[i]);
        v.default_lower += dv[i] < bv[i] ? 1 : 0;
      }
      v.paired_gap = grid_spread_of(gaps);
      verdicts.push_back(v);
    }
  }
  return verdicts;
}

std::string grid_markdown(const GridResult& grid, const std::string& settings) {
  const std::vector<GridCell> cells = grid_cells(grid);
  std::string md = fmt::format(
      "Variant grid, tracker `{}`: {} semi-real variants x {} masks x {} screens = {} runs{}; "
      "{}.\n\n",
      grid.tracker, grid.variants.size(), grid.masks.size(), grid.screens.size(), grid.runs.size(),
      grid.complete ? "" : " (INCOMPLETE: interrupted)", settings);
  md +=
      "| variant | depth [m] | motion [px/frame] | start [px] | parallax-hidden frames "
      "(residual < 2.45 px) |\n|---|---:|---:|---:|---|\n";
  for (const GridVariant& v : grid.variants) {
    std::string frames;
    for (std::size_t i = 1; i < v.parallax_px.size(); ++i) {
      if (v.parallax_px[i] < kHiddenParallaxPx) {
        frames += fmt::format("{}{} ({:.1f})", frames.empty() ? "" : ", ", i, v.parallax_px[i]);
      }
    }
    md += fmt::format("| {} | {:.1f} | {:+.1f} | {:.0f} | {} |\n", v.variant.name,
                      v.variant.depth_m, v.variant.speed_px_per_frame, v.variant.start_x_px,
                      frames.empty() ? "none" : frames);
  }
  md +=
      "\nMean ± sd over the variants; person and static shares pooled over them.\n\n"
      "| mask | screen | ATE RMSE [cm] | RPE trans [mm/frame] | person matches kept [%] | static "
      "matches lost [%] |\n|---|---|---:|---:|---:|---:|\n";
  for (const GridCell& c : cells) {
    md += fmt::format("| {} | {} | {} | {} | {} | {:.1f} |\n", c.mask, c.screen, grid_pm(c.ate_cm),
                      grid_pm(c.rpe_mm), grid_share(c.person_survivors, c.person_matches),
                      c.static_matches == 0 ? 0.0
                                            : 100.0 * static_cast<double>(c.static_dropped) /
                                                  static_cast<double>(c.static_matches));
  }
  md +=
      "\nThe default against the best other screen per mask (best: its mean is lower; tied: the "
      "gap "
      "is within the larger sd over the variants; paired: default minus that screen on each "
      "variant).\n\n"
      "| mask | metric | best other screen | its mean | default | gap | spread | verdict | paired "
      "gap | "
      "default lower in |\n|---|---|---|---:|---:|---:|---:|---|---:|---:|\n";
  for (const GridVerdict& v : grid_verdicts(grid, cells)) {
    md += fmt::format("| {} | {} | {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {} | {} | {} of {} |\n",
                      v.mask, v.metric, v.best_screen, v.best_mean, v.default_mean,
                      v.default_mean - v.best_mean, v.spread, v.verdict, grid_pm(v.paired_gap),
                      v.default_lower, v.paired_gap.n);
  }
  md +=
      "\nPerson matches kept in the parallax-hidden frames against the other frames (all "
      "variants).\n\n| mask | screen | kept in hidden frames [%] | kept in other frames [%] |\n"
      "|---|---|---:|---:|\n";
  for (const GridCell& c : cells) {
    md += fmt::format("| {} | {} | {} | {} |\n", c.mask, c.screen,
                      grid_share(c.hidden_survivors, c.hidden_matches),
                      grid_share(c.other_survivors, c.other_matches));
  }
  return md;
}

nlohmann::json grid_json(const GridResult& grid, const std::string& settings) {
  const std::vector<GridCell> cells = grid_cells(grid);
  nlohmann::json j;
  j["tracker"] = grid.tracker;
  j["frames"] = grid.frames;
  j["settings"] = settings;
  j["complete"] = grid.complete;
  j["hidden_parallax_px"] = kHiddenParallaxPx;
  j["variants"] = nlohmann::json::array();
  for (const GridVariant& v : grid.variants) {
    nlohmann::json parallax = nlohmann::json::array();
    for (const double p : v.parallax_px) {
      parallax.push_back(std::isfinite(p) ? nlohmann::json(p) : nlohmann::json(nullptr));
    }
    j["variants"].push_back({{"name", v.variant.name},
                             {"depth_m", v.variant.depth_m},
                             {"speed_px_per_frame", v.variant.speed_px_per_frame},
                             {"start_x_px", v.variant.start_x_px},
                             {"parallax_px", parallax}});
  }
  j["runs"] = nlohmann::json::array();
  for (const GridRun& r : grid.runs) j["runs"].push_back(to_json(r));
  j["cells"] = nlohmann::json::array();
  for (const GridCell& c : cells) {
    j["cells"].push_back({{"mask", c.mask},
                          {"screen", c.screen},
                          {"ate_cm", grid_spread_json(c.ate_cm)},
                          {"rpe_mm_per_frame", grid_spread_json(c.rpe_mm)},
                          {"person_matches", c.person_matches},
                          {"person_survivors", c.person_survivors},
                          {"static_matches", c.static_matches},
                          {"static_dropped", c.static_dropped},
                          {"hidden_person_matches", c.hidden_matches},
                          {"hidden_person_survivors", c.hidden_survivors},
                          {"other_person_matches", c.other_matches},
                          {"other_person_survivors", c.other_survivors}});
  }
  j["verdicts"] = nlohmann::json::array();
  for (const GridVerdict& v : grid_verdicts(grid, cells)) {
    j["verdicts"].push_back({{"mask", v.mask},
                             {"metric", v.metric},
                             {"best_screen", v.best_screen},
                             {"best_mean", v.best_mean},
                             {"default_mean", v.default_mean},
                             {"spread", v.spread},
                             {"verdict", v.verdict},
                             {"paired_gap", grid_spread_json(v.paired_gap)},
                             {"default_lower", v.default_lower}});
  }
  return j;
}

}  // namespace hbos::slam
