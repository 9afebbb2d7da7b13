#include "case_metrics.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace hbos::cases {

namespace {

std::size_t index_of(const std::vector<NamedScreen>& strategies, const char* name) {
  for (std::size_t k = 0; k < strategies.size(); ++k)
    if (strategies[k].name == name) return k;
  throw InvalidArgument(fmt::format("the acceptance rule needs a strategy named '{}'", name));
}

}  // namespace

double quantile_of(std::vector<double> values, double q) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const double at = q * static_cast<double>(values.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(at));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  const double w = at - static_cast<double>(lo);
  return (1.0 - w) * values[lo] + w * values[hi];
}

CaseMetrics measure_case(const hbos_test::ScreeningCase& c,
                         const std::vector<NamedScreen>& strategies) {
  CaseMetrics m;
  m.pairs = static_cast<int>(c.pairs.size());
  m.tallies.resize(strategies.size());
  std::vector<hbos::ReprojectionScreend> screens;
  for (const NamedScreen& s : strategies) screens.emplace_back(s.config);
  std::vector<double> person;
  for (const hbos_test::CasePair& pair : c.pairs) {
    if (pair.size() == 0) continue;
    m.matches += pair.size();
    person.clear();
    for (Eigen::Index i = 0; i < pair.size(); ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (pair.dynamic[k] != 0) {
        person.push_back(pair.whitened_residual(i));
      } else if (pair.gross[k] == 0) {
        m.static_whitened.push_back(pair.whitened_residual(i));
      }
    }
    if (static_cast<int>(person.size()) >= kMinDynamicForAbsorbed) {
      ++m.pairs_with_person;
      if (quantile_of(person, 0.5) < kChi2GatePx) ++m.pairs_absorbed;
    }
    for (std::size_t s = 0; s < screens.size(); ++s) {
      const hbos::ScreenResult<double>& r = screens[s].screen(pair.matches);
      for (Eigen::Index i = 0; i < pair.size(); ++i)
        hbos_test::count_match(m.tallies[s], pair, i, r.inlier(i));
    }
  }
  return m;
}

void measure_equal_loss(const hbos_test::ScreeningCase& c,
                        const std::vector<NamedScreen>& strategies, CaseMetrics& m) {
  const double default_loss = m.tallies[index_of(strategies, "default")].static_dropped_pct();
  const double chi2_loss = m.tallies[index_of(strategies, "chi2")].static_dropped_pct();
  hbos::ReprojectionScreend with_history(strategies[index_of(strategies, "default")].config);
  m.default_with_history = hbos_test::tally_case_with_history(c, with_history);
  const double history_loss = m.default_with_history.static_dropped_pct();
  m.equal_loss.clear();
  for (const hbos_test::GateSetting& g : hbos_test::gate_settings()) {
    m.equal_loss.push_back({g.screen, g.setting, hbos_test::at_static_loss(c, g, default_loss),
                            hbos_test::at_static_loss(c, g, chi2_loss),
                            hbos_test::at_static_loss(c, g, history_loss)});
  }
}

namespace {

Verdict acceptance_of(const Tally& d, const CaseMetrics& m,
                      const std::vector<NamedScreen>& strategies) {
  const Tally& chi2 = m.tallies[index_of(strategies, "chi2")];
  const Tally& q = m.tallies[index_of(strategies, "quantile")];
  Verdict v;
  std::vector<std::string> failed;
  if (m.static_sequence) {
    const double limit = chi2.static_dropped_pct() + 0.5;
    if (!(d.static_dropped_pct() <= limit)) {
      failed.push_back(fmt::format("static loss {:.1f} % > chi2 {:.1f} % + 0.5",
                                   d.static_dropped_pct(), chi2.static_dropped_pct()));
    }
  } else {
    if (!(d.static_dropped_pct() <= chi2.static_dropped_pct())) {
      failed.push_back(fmt::format("static loss {:.1f} % > chi2 {:.1f} %", d.static_dropped_pct(),
                                   chi2.static_dropped_pct()));
    }
    if (d.dynamics > 0) {
      if (!(d.dynamic_kept_pct() < chi2.dynamic_kept_pct())) {
        failed.push_back(fmt::format("dynamic kept {:.1f} % >= chi2 {:.1f} %", d.dynamic_kept_pct(),
                                     chi2.dynamic_kept_pct()));
      }
      if (!(d.dynamic_kept_pct() < q.dynamic_kept_pct())) {
        failed.push_back(fmt::format("dynamic kept {:.1f} % >= quantile {:.1f} %",
                                     d.dynamic_kept_pct(), q.dynamic_kept_pct()));
      }
    }
  }
  v.pass = failed.empty();
  for (const std::string& f : failed) v.reason += (v.reason.empty() ? "" : "; ") + f;
  if (v.pass) {
    v.reason = m.static_sequence ? "static loss within chi2 + 0.5"
               : d.dynamics > 0  ? "fewer dynamics than chi2 and quantile, static loss <= chi2"
                                 : "no dynamic match: static loss <= chi2";
  }
  return v;
}

}  // namespace

Verdict acceptance(const CaseMetrics& m, const std::vector<NamedScreen>& strategies) {
  return acceptance_of(m.tallies[index_of(strategies, "default")], m, strategies);
}

Verdict acceptance_with_history(const CaseMetrics& m, const std::vector<NamedScreen>& strategies) {
  return acceptance_of(m.default_with_history, m, strategies);
}

}  // namespace hbos::cases
