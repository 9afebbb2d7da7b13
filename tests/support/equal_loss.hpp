#pragma once
/// \file
/// Screens compared at equal static loss on a labelled real case (tests/data/screening_cases).
///
/// A gate's one setting (chi^2's threshold, the fixed gate's pixels, the quantile, MAD's k)
/// trades static matches lost against dynamic matches kept. Comparing the default with each
/// baseline at the baseline's usual setting mixes two things: how well a screen separates the
/// two kinds, and where on its own trade-off curve it sits. Here each baseline's setting is
/// swept, per case, to the most aggressive value whose pooled static loss does not exceed a
/// target (the default's loss, or chi^2's), and the dynamics it then keeps are reported. The
/// sweep sees the labels, so it favours the baseline: no deployed gate can be tuned per case.
/// Shared by hbos-screening-eval and tests/unit/test_screen_real_cases.cpp. Test support, not
/// part of the library.

#include <hbos/screening.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "screening_cases.hpp"

namespace hbos_test {

/// Pooled counts of one screen on one case, single round per pair. Static = neither dynamic nor
/// gross.
struct CaseTally {
  long long statics = 0, static_dropped = 0;
  long long dynamics = 0, dynamic_kept = 0;
  long long gross = 0, gross_kept = 0;

  [[nodiscard]] static double pct(long long part, long long whole) {
    return whole == 0 ? std::numeric_limits<double>::quiet_NaN()
                      : 100.0 * static_cast<double>(part) / static_cast<double>(whole);
  }
  [[nodiscard]] double static_dropped_pct() const { return pct(static_dropped, statics); }
  [[nodiscard]] double dynamic_kept_pct() const { return pct(dynamic_kept, dynamics); }
  [[nodiscard]] double gross_kept_pct() const { return pct(gross_kept, gross); }
};

/// Adds match i of `pair`, kept or not, to `t`.
inline void count_match(CaseTally& t, const CasePair& pair, Eigen::Index i, bool kept) {
  const auto k = static_cast<std::size_t>(i);
  if (pair.dynamic[k] != 0) {
    ++t.dynamics;
    t.dynamic_kept += kept ? 1 : 0;
  } else if (pair.gross[k] != 0) {
    ++t.gross;
    t.gross_kept += kept ? 1 : 0;
  } else {
    ++t.statics;
    t.static_dropped += kept ? 0 : 1;
  }
}

/// Screens every pair of `c` once with `screen` and counts.
[[nodiscard]] inline CaseTally tally_case(const ScreeningCase& c,
                                          hbos::ReprojectionScreend& screen) {
  CaseTally t;
  for (const CasePair& pair : c.pairs) {
    if (pair.size() == 0) continue;
    const hbos::ScreenResult<double>& r = screen.screen(pair.matches);
    for (Eigen::Index i = 0; i < pair.size(); ++i) count_match(t, pair, i, r.inlier(i));
  }
  return t;
}

/// Screens the pairs of `c` in order as a tracker with memory would: each track (the pairs'
/// track_id chains) keeps the forgetting-weighted share of its screenings that rejected it,
/// share = sum_k f^k r_k / sum_k f^k (r_k = 1 when screened out k screenings ago), as the map
/// tracker's ScreeningHistory does (examples/slam/frontend/map/screening_history.hpp), and each
/// match whose track was screened before carries that share as its outlier history
/// (Matches::set_outlier_history). The screen stays stateless; this loop is the caller.
[[nodiscard]] inline CaseTally tally_case_with_history(const ScreeningCase& c,
                                                       hbos::ReprojectionScreend& screen,
                                                       double forgetting = 0.8) {
  struct Memory {
    double rejections = 0.0, screenings = 0.0;
  };
  std::unordered_map<int, Memory> memory, next;
  hbos::Matchesd matches;
  CaseTally t;
  for (const CasePair& pair : c.pairs) {
    if (pair.size() == 0) continue;
    matches = pair.matches;
    for (Eigen::Index i = 0; i < pair.size(); ++i) {
      const auto it = memory.find(pair.track_id[static_cast<std::size_t>(i)]);
      if (it != memory.end())
        matches.set_outlier_history(i, it->second.rejections / it->second.screenings);
    }
    const hbos::ScreenResult<double>& r = screen.screen(matches);
    next.clear();
    for (Eigen::Index i = 0; i < pair.size(); ++i) {
      const auto k = static_cast<std::size_t>(i);
      const bool kept = r.inlier(i);
      if (pair.track_id[k] >= 0) {
        const auto it = memory.find(pair.track_id[k]);
        Memory m = it == memory.end() ? Memory{} : it->second;
        m.rejections = forgetting * m.rejections + (kept ? 0.0 : 1.0);
        m.screenings = forgetting * m.screenings + 1.0;
        next[pair.track_id[k]] = m;
      }
      count_match(t, pair, i, kept);
    }
    memory.swap(next);
  }
  return t;
}

/// One baseline's setting: a larger value keeps more matches (a wider gate), so the static loss
/// does not increase with it.
struct GateSetting {
  std::string screen;         ///< the name table's name (chi2, fixed, quantile, mad)
  std::string setting;        ///< what the value is, for the tables
  double lo = 0.0, hi = 0.0;  ///< the swept range, lo > 0; searched on a log scale
  std::function<hbos::ScreenStrategy(double)> make;
};

/// The four baselines of the name table, each with its one setting.
[[nodiscard]] inline std::vector<GateSetting> gate_settings() {
  return {
      {"chi2", "chi^2 threshold", 1e-3, 1e4,
       [](double x) {
         hbos::ChiSquareGate g;
         g.chi2_mono = x;
         g.chi2_stereo = x * (7.815 / 5.991);
         return hbos::ScreenStrategy(g);
       }},
      {"fixed", "max px", 1e-3, 1e3,
       [](double x) { return hbos::ScreenStrategy(hbos::FixedPixelGate{x}); }},
      {"quantile", "quantile", 1e-3, 1.0,
       [](double x) {
         hbos::QuantileGate g;
         g.quantile = x;
         return hbos::ScreenStrategy(g);
       }},
      {"mad", "k", 1e-3, 1e3,
       [](double x) {
         hbos::MadGate g;
         g.k = x;
         return hbos::ScreenStrategy(g);
       }},
  };
}

/// A baseline at a target static loss.
struct AtStaticLoss {
  double target_pct = 0.0;  ///< the static loss it may not exceed [%]
  /// the most aggressive setting found within the target; NaN when even the widest gate of the
  /// range loses more statics than the target
  double value = std::numeric_limits<double>::quiet_NaN();
  CaseTally tally;  ///< the case's counts at that setting
};

/// Sweeps `g` on `c` (bisection on a log scale, `steps` halvings) to the smallest setting whose
/// pooled static loss is at most `target_pct`.
[[nodiscard]] inline AtStaticLoss at_static_loss(const ScreeningCase& c, const GateSetting& g,
                                                 double target_pct, int steps = 40) {
  AtStaticLoss out;
  out.target_pct = target_pct;
  const auto run = [&](double x) {
    hbos::ReprojectionScreend screen(g.make(x));
    return tally_case(c, screen);
  };
  CaseTally widest = run(g.hi);
  if (!(widest.static_dropped_pct() <= target_pct)) return out;
  double lo = std::log(g.lo), hi = std::log(g.hi);
  CaseTally at_hi = widest;
  const CaseTally at_lo = run(g.lo);
  if (at_lo.static_dropped_pct() <= target_pct) {
    out.value = g.lo;
    out.tally = at_lo;
    return out;
  }
  for (int s = 0; s < steps; ++s) {
    const double mid = 0.5 * (lo + hi);
    const CaseTally t = run(std::exp(mid));
    if (t.static_dropped_pct() <= target_pct) {
      hi = mid;
      at_hi = t;
    } else {
      lo = mid;
    }
  }
  out.value = std::exp(hi);
  out.tally = at_hi;
  return out;
}

}  // namespace hbos_test
