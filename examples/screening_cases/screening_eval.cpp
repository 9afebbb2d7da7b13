// hbos-screening-eval CASES_DIR: every screen strategy (eval_strategies.hpp), single round, on
// every case of a labelled case folder (cases.json), as Markdown and JSON, with the acceptance
// rule of issue 7 item 7 per case. See docs/screening_cases.md.
#include "case_metrics.hpp"
#include "common/atomic_file.hpp"
#include "common/tool_main.hpp"

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <hbos/error.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <utility>

namespace {

namespace fs = std::filesystem;
using hbos::cases::CaseMetrics;
using hbos::cases::NamedScreen;

std::string cell(double x) { return std::isnan(x) ? "-" : fmt::format("{:.1f}", x); }

nlohmann::ordered_json number(double x) {
  return std::isnan(x) ? nlohmann::ordered_json(nullptr)
                       : nlohmann::ordered_json(std::round(x * 1000.0) / 1000.0);
}

nlohmann::ordered_json read_manifest(const std::string& dir) {
  const std::string path = (fs::path(dir) / "cases.json").string();
  std::ifstream in(path);
  if (!in) throw hbos::InvalidArgument(fmt::format("cannot open manifest '{}'", path));
  nlohmann::ordered_json m;
  try {
    in >> m;
  } catch (const nlohmann::json::exception& e) {
    throw hbos::InvalidArgument(fmt::format("manifest '{}' is not valid JSON: {}", path, e.what()));
  }
  if (!m.contains("cases") || !m["cases"].is_array() || m["cases"].empty()) {
    throw hbos::InvalidArgument(fmt::format("manifest '{}' lists no cases", path));
  }
  if (m.contains("format") && m["format"] != 1) {
    throw hbos::InvalidArgument(
        fmt::format("manifest '{}': format {} is not supported (1 is)", path, m["format"].dump()));
  }
  std::size_t index = 0;
  for (const auto& c : m["cases"]) {
    // Every field the tables read, with its type: a wrong one is named here, not by the JSON
    // library's "type must be string" somewhere later.
    const std::string which =
        fmt::format("manifest '{}', case {}{}", path, index,
                    c.is_object() && c.contains("name") && c["name"].is_string()
                        ? " ('" + c["name"].get<std::string>() + "')"
                        : std::string());
    if (!c.is_object()) throw hbos::InvalidArgument(which + ": is not an object");
    const auto field = [&](const char* key) -> const nlohmann::ordered_json& {
      if (!c.contains(key))
        throw hbos::InvalidArgument(fmt::format("{}: no field '{}'", which, key));
      return c[key];
    };
    for (const char* key : {"name", "dir", "rough_pose", "mask"}) {
      if (!field(key).is_string() || field(key).get<std::string>().empty()) {
        throw hbos::InvalidArgument(fmt::format("{}: field '{}' must be a non-empty string, got {}",
                                                which, key, field(key).dump()));
      }
    }
    const std::string mask = c["mask"].get<std::string>();
    if (mask != "none" && mask != "exact" && mask != "degraded") {
      throw hbos::InvalidArgument(
          fmt::format("{}: field 'mask' must be none, exact or degraded, got '{}'", which, mask));
    }
    const auto& people = field("people");
    if (!people.is_array() ||
        std::any_of(people.begin(), people.end(), [](const auto& p) { return !p.is_string(); })) {
      throw hbos::InvalidArgument(fmt::format(
          "{}: field 'people' must be an array of names, got {}", which, people.dump()));
    }
    if (c.contains("pairs") &&
        (!c["pairs"].is_number_integer() || c["pairs"].get<long long>() < 1)) {
      throw hbos::InvalidArgument(fmt::format(
          "{}: field 'pairs' must be a positive integer, got {}", which, c["pairs"].dump()));
    }
    if (c.contains("seed") && !c["seed"].is_number_unsigned()) {
      throw hbos::InvalidArgument(fmt::format(
          "{}: field 'seed' must be a non-negative integer, got {}", which, c["seed"].dump()));
    }
    ++index;
  }
  return m;
}

// The acceptance rule's verdict per case, as `verdict` gives it, and the count that pass.
template <class Verdict>
std::string acceptance_table(const std::vector<CaseMetrics>& all, Verdict verdict) {
  std::string md = "| case | result | why |\n|---|---|---|\n";
  int passed = 0;
  for (const CaseMetrics& m : all) {
    const auto v = verdict(m);
    passed += v.pass ? 1 : 0;
    md += fmt::format("| {} | {} | {} |\n", m.name, v.pass ? "pass" : "FAIL", v.reason);
  }
  return md + fmt::format("\n{} of {} cases pass.\n", passed, all.size());
}

// One baseline at a screen's static loss: the dynamics it keeps (its setting), and whether the
// screen, keeping `kept` %, keeps fewer (✓) or not (✗).
std::string at_loss_cell(const hbos_test::AtStaticLoss& at, double kept, bool static_sequence) {
  if (std::isnan(at.value)) return "unreachable";
  const double other = at.tally.dynamic_kept_pct();
  std::string c = fmt::format("{} ({:.3g})", cell(other), at.value);
  if (!std::isnan(kept) && !std::isnan(other) && !static_sequence) c += kept < other ? " ✓" : " ✗";
  return c;
}

// A table of the baselines at one screen's static loss: `tally` picks the screen's counts in a
// case, `at` the baselines' sweep to its loss.
template <class Tally, class At>
std::string equal_loss_table(const std::vector<CaseMetrics>& all, const std::string& screen,
                             Tally tally, At at, bool quantile_at_chi2) {
  std::string md = "| case | " + screen + " |";
  for (const auto& e : all.front().equal_loss) md += " " + e.screen + " at its loss |";
  md += quantile_at_chi2 ? " quantile at chi2's loss |\n|---|---|" : "\n|---|---|";
  for (std::size_t k = 0; k < all.front().equal_loss.size() + (quantile_at_chi2 ? 1 : 0); ++k)
    md += "---|";
  md += "\n";
  int with_person = 0, beyond_all = 0;
  for (const CaseMetrics& m : all) {
    const hbos::cases::Tally& d = tally(m);
    const double kept = d.dynamic_kept_pct();
    md += fmt::format("| {} | {} / {} |", m.name, cell(d.static_dropped_pct()), cell(kept));
    bool all_beaten = !std::isnan(kept);
    const hbos::cases::EqualLoss* quantile = nullptr;
    for (const auto& e : m.equal_loss) {
      md += " " + at_loss_cell(at(e), kept, m.static_sequence) + " |";
      const double other = at(e).tally.dynamic_kept_pct();
      all_beaten = all_beaten && !std::isnan(other) && kept < other;
      if (e.screen == "quantile") quantile = &e;
    }
    if (quantile_at_chi2) {
      const hbos_test::AtStaticLoss* q = quantile == nullptr ? nullptr : &quantile->at_chi2;
      md += q == nullptr || std::isnan(q->value)
                ? std::string(" - |")
                : fmt::format(" {} / {} ({:.3g}) |", cell(q->tally.static_dropped_pct()),
                              cell(q->tally.dynamic_kept_pct()), q->value);
    }
    md += "\n";
    if (!std::isnan(kept)) {
      ++with_person;
      beyond_all += all_beaten ? 1 : 0;
    }
  }
  md += fmt::format(
      "\nIn {} of {} cases with dynamic matches, {} keeps fewer than every baseline at its "
      "static loss.\n",
      beyond_all, with_person, screen);
  return md;
}

std::string equal_loss_markdown(const std::vector<CaseMetrics>& all,
                                const std::vector<NamedScreen>& strategies) {
  std::size_t default_at = 0;
  while (default_at < strategies.size() && strategies[default_at].name != "default") ++default_at;
  if (all.empty() || all.front().equal_loss.empty() || default_at == strategies.size()) return {};
  std::string md =
      "\n#### The baselines at the default's static loss\n\n"
      "Each baseline's one setting (in brackets: chi2's threshold, the fixed gate's pixels, the "
      "quantile, MAD's k) swept per case to the most aggressive value whose pooled static loss "
      "does not exceed the default's; cells: dynamic matches kept % at that setting (✓: the "
      "default keeps fewer). The sweep sees the labels, which favours the baseline. Last "
      "column: the quantile gate swept to chi2's own static loss.\n\n";
  md += equal_loss_table(
      all, "default", [&](const CaseMetrics& m) -> const auto& { return m.tallies[default_at]; },
      [](const hbos::cases::EqualLoss& e) -> const auto& { return e.at_default; }, true);
  md +=
      "\n#### Persistence: the default with the caller's outlier history\n\n"
      "The pairs screened in order; each track keeps the forgetting-weighted (0.8) share of its "
      "screenings that rejected it, as the map tracker does, and passes it as the match's "
      "outlier history (HistoryEvidence fires above 0.5, beyond one noise scale). The "
      "baselines are swept to this screen's static loss.\n\n";
  md += equal_loss_table(
      all, "default + history",
      [](const CaseMetrics& m) -> const auto& { return m.default_with_history; },
      [](const hbos::cases::EqualLoss& e) -> const auto& { return e.at_default_with_history; },
      false);
  md += "\nThe acceptance rule (issue 7 item 7) with these counts in place of the default's:\n\n";
  md += acceptance_table(all, [&](const CaseMetrics& m) {
    return hbos::cases::acceptance_with_history(m, strategies);
  });
  return md;
}

// One row of the disagreement table: the counts, then medians of the reference residuals.
std::string disagreement_row(const std::string& name, const hbos_test::StaticDisagreement& d) {
  const auto pct = [](long part, long whole) {
    return whole > 0 ? fmt::format("{:.0f}",
                                   100.0 * static_cast<double>(part) / static_cast<double>(whole))
                     : std::string("-");
  };
  const auto med = [](const std::vector<double>& v) {
    const double m = hbos_test::median_of(v);
    return std::isnan(m) ? std::string("-") : fmt::format("{:.2f}", m);
  };
  return fmt::format("| {} | {} | {} | {} | {} ({}) | {} | {} | {} ({}) | {} | {} |\n", name,
                     d.statics, pct(d.beside_person, d.statics), d.only_default_by_gate,
                     d.only_default_by_evidence,
                     pct(d.only_default_by_evidence_beside, d.only_default_by_evidence),
                     med(d.evidence_reference), med(d.evidence_along_person), d.only_chi2,
                     med(d.chi2_reference), med(d.all_reference), med(d.beside_along_person));
}

// The cases with a person pooled per rough pose: (RANSAC, perturbed GT).
std::pair<hbos_test::StaticDisagreement, hbos_test::StaticDisagreement> pooled_disagreement(
    const std::vector<CaseMetrics>& all) {
  hbos_test::StaticDisagreement ransac, pgt;
  for (const CaseMetrics& m : all) {
    if (m.static_sequence) continue;
    if (m.rough_pose == "ransac") ransac += m.disagreement;
    if (m.rough_pose == "pgt") pgt += m.disagreement;
  }
  return {ransac, pgt};
}

std::string disagreement_markdown(const std::vector<CaseMetrics>& all) {
  std::string md =
      "\n#### The statics the default and chi2 disagree on\n\n"
      "Single round, the default against chi2 (5.991). Static = the labels' (neither keypoint on "
      "a person, reference residual within 3 sigma). Beside a person: the keypoint within 15 px "
      "(ORB's patch radius) of a dynamic keypoint of the same frame. Residuals are under the "
      "reference pose, |r| / sigma [px/sigma]; 'along': the component along the nearest dynamic "
      "keypoint's reference residual (how far the match moves with the person). Columns: "
      "statics; % beside a person; dropped only by the default beyond its gate; dropped only by "
      "its evidence inside the gate (% beside a person); their median residual and along; "
      "dropped only by chi2 (their median residual); every static's median residual; the "
      "median along of the statics beside a person.\n\n"
      "| case | statics | beside % | default only, gate | default only, evidence (beside %) | "
      "evidence: residual | evidence: along | chi2 only (residual) | all: residual | beside: "
      "along |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const CaseMetrics& m : all) md += disagreement_row(m.name, m.disagreement);
  const auto [ransac, pgt] = pooled_disagreement(all);
  if (ransac.statics > 0) md += disagreement_row("cases with a person, RANSAC", ransac);
  if (pgt.statics > 0) md += disagreement_row("cases with a person, perturbed GT", pgt);
  return md;
}

std::string markdown(const std::vector<CaseMetrics>& all, const nlohmann::ordered_json& cases,
                     const std::vector<NamedScreen>& strategies) {
  std::string md = "#### Screens on the labelled real residual cases (single round)\n\n";
  md +=
      "Cells: static matches dropped % / dynamic matches kept % / gross mismatches kept %, pooled "
      "over the case's pairs ('-': none of that kind).\n\n| case | mask | pose | pairs | matches |";
  for (const NamedScreen& s : strategies) md += " " + s.name + " |";
  md += "\n|---|---|---|---|---|";
  for (std::size_t k = 0; k < strategies.size(); ++k) md += "---|";
  md += "\n";
  for (std::size_t c = 0; c < all.size(); ++c) {
    const CaseMetrics& m = all[c];
    md += fmt::format("| {} | {} | {} | {} | {} |", m.name, cases[c]["mask"].get<std::string>(),
                      m.rough_pose, m.pairs, m.matches);
    for (const auto& t : m.tallies) {
      md += fmt::format(" {} / {} / {} |", cell(t.static_dropped_pct()), cell(t.dynamic_kept_pct()),
                        cell(t.gross_kept_pct()));
    }
    md += "\n";
  }
  md +=
      "\n#### Acceptance (issue 7 item 7) per case\n\n"
      "Static sequence: default's static loss within chi2's + 0.5 points. Otherwise: default "
      "keeps fewer dynamics than chi2 and than the 0.8 quantile at no more static loss than "
      "chi2.\n\n";
  md += acceptance_table(
      all, [&](const CaseMetrics& m) { return hbos::cases::acceptance(m, strategies); });
  md += equal_loss_markdown(all, strategies);
  md += disagreement_markdown(all);
  md +=
      "\n#### The rough pose and the noise\n\n"
      "Absorbed: pairs with >= 10 dynamic matches whose median whitened person residual under "
      "the rough pose is below 2.447 px/sigma (chi2's gate). Static tail: quantiles of |r| / "
      "sigma of the static matches (not gross) under the rough pose [px/sigma].\n\n"
      "| case | pairs with person | absorbed | static q50 | q90 | q95 | q99 |\n"
      "|---|---|---|---|---|---|---|\n";
  std::vector<double> ransac_static;
  for (const CaseMetrics& m : all) {
    md += fmt::format("| {} | {} | {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} |\n", m.name,
                      m.pairs_with_person, m.pairs_absorbed,
                      hbos::cases::quantile_of(m.static_whitened, 0.5),
                      hbos::cases::quantile_of(m.static_whitened, 0.9),
                      hbos::cases::quantile_of(m.static_whitened, 0.95),
                      hbos::cases::quantile_of(m.static_whitened, 0.99));
    if (m.rough_pose == "ransac")
      ransac_static.insert(ransac_static.end(), m.static_whitened.begin(), m.static_whitened.end());
  }
  if (!ransac_static.empty()) {
    md += fmt::format("| all RANSAC cases | | | {:.2f} | {:.2f} | {:.2f} | {:.2f} |\n",
                      hbos::cases::quantile_of(ransac_static, 0.5),
                      hbos::cases::quantile_of(ransac_static, 0.9),
                      hbos::cases::quantile_of(ransac_static, 0.95),
                      hbos::cases::quantile_of(ransac_static, 0.99));
  }
  return md;
}

// The disagreement counts, and the reference residuals' quantiles [q10, q25, q50, q75, q90]
// (interpolated; a figure's boxes). The Markdown's medians are hbos_test::median_of's (the
// upper middle value), which can differ from q50 in the last digit of a small sample.
nlohmann::ordered_json disagreement_json(const hbos_test::StaticDisagreement& d) {
  const auto quantiles = [](const std::vector<double>& v) {
    nlohmann::ordered_json q = nlohmann::ordered_json::array();
    for (const double p : {0.1, 0.25, 0.5, 0.75, 0.9})
      q.push_back(number(hbos::cases::quantile_of(v, p)));  // NaN (null) when empty
    return q;
  };
  return {{"statics", d.statics},
          {"beside_person", d.beside_person},
          {"only_default_by_gate", d.only_default_by_gate},
          {"only_default_by_evidence", d.only_default_by_evidence},
          {"only_default_by_evidence_beside_person", d.only_default_by_evidence_beside},
          {"only_chi2", d.only_chi2},
          {"reference_residual_quantiles",
           {{"all", quantiles(d.all_reference)},
            {"only_default_by_evidence", quantiles(d.evidence_reference)},
            {"only_chi2", quantiles(d.chi2_reference)}}},
          {"median_along_person",
           {{"only_default_by_evidence", number(hbos_test::median_of(d.evidence_along_person))},
            {"beside_person", number(hbos_test::median_of(d.beside_along_person))}}}};
}

nlohmann::ordered_json to_json(const std::vector<CaseMetrics>& all,
                               const std::vector<NamedScreen>& strategies) {
  nlohmann::ordered_json out;
  out["strategies"] = nlohmann::ordered_json::array();
  for (const NamedScreen& s : strategies) out["strategies"].push_back(s.name);
  out["cases"] = nlohmann::ordered_json::array();
  for (const CaseMetrics& m : all) {
    nlohmann::ordered_json c;
    c["name"] = m.name;
    c["scene"] = m.scene;
    c["rough_pose"] = m.rough_pose;
    c["static_sequence"] = m.static_sequence;
    c["pairs"] = m.pairs;
    c["matches"] = m.matches;
    for (std::size_t s = 0; s < strategies.size(); ++s) {
      const auto& t = m.tallies[s];
      c["strategies"][strategies[s].name] = {
          {"statics", t.statics},   {"static_dropped_pct", number(t.static_dropped_pct())},
          {"dynamics", t.dynamics}, {"dynamic_kept_pct", number(t.dynamic_kept_pct())},
          {"gross", t.gross},       {"gross_kept_pct", number(t.gross_kept_pct())}};
    }
    const auto v = hbos::cases::acceptance(m, strategies);
    c["acceptance"] = {{"pass", v.pass}, {"reason", v.reason}};
    const auto vh = hbos::cases::acceptance_with_history(m, strategies);
    c["acceptance_with_history"] = {{"pass", vh.pass}, {"reason", vh.reason}};
    for (const auto& e : m.equal_loss) {
      const auto at = [&](const hbos_test::AtStaticLoss& a) {
        return nlohmann::ordered_json{{"target_static_dropped_pct", number(a.target_pct)},
                                      {"value", number(a.value)},
                                      {"static_dropped_pct", number(a.tally.static_dropped_pct())},
                                      {"dynamic_kept_pct", number(a.tally.dynamic_kept_pct())},
                                      {"gross_kept_pct", number(a.tally.gross_kept_pct())}};
      };
      c["equal_loss"][e.screen] = {{"setting", e.setting},
                                   {"at_default", at(e.at_default)},
                                   {"at_chi2", at(e.at_chi2)},
                                   {"at_default_with_history", at(e.at_default_with_history)}};
    }
    const auto& h = m.default_with_history;
    c["default_with_history"] = {
        {"statics", h.statics},   {"static_dropped_pct", number(h.static_dropped_pct())},
        {"dynamics", h.dynamics}, {"dynamic_kept_pct", number(h.dynamic_kept_pct())},
        {"gross", h.gross},       {"gross_kept_pct", number(h.gross_kept_pct())}};
    c["static_disagreement"] = disagreement_json(m.disagreement);
    c["pairs_with_person"] = m.pairs_with_person;
    c["pairs_absorbed"] = m.pairs_absorbed;
    c["static_whitened_quantiles"] = {
        {"q50", number(hbos::cases::quantile_of(m.static_whitened, 0.5))},
        {"q90", number(hbos::cases::quantile_of(m.static_whitened, 0.9))},
        {"q95", number(hbos::cases::quantile_of(m.static_whitened, 0.95))},
        {"q99", number(hbos::cases::quantile_of(m.static_whitened, 0.99))}};
    out["cases"].push_back(c);
  }
  const auto [ransac, pgt] = pooled_disagreement(all);
  out["static_disagreement_pooled"] = {{"ransac", disagreement_json(ransac)},
                                       {"pgt", disagreement_json(pgt)}};
  return out;
}

int run(int argc, char** argv) {
  CLI::App app{"Every screen strategy on labelled real residual cases.", "hbos-screening-eval"};
  std::string dir, markdown_path = "-", json_path;
  app.add_option("cases_dir", dir, "folder with cases.json (e.g. tests/data/screening_cases)")
      ->required();
  app.add_option("--markdown", markdown_path, "Markdown report ('-' = stdout)")
      ->capture_default_str();
  app.add_option("--json", json_path, "JSON report");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  const nlohmann::ordered_json manifest = read_manifest(dir);
  const std::vector<NamedScreen> strategies = hbos::cases::eval_strategies();
  std::vector<CaseMetrics> all;
  for (const auto& c : manifest["cases"]) {
    const auto pose = hbos_test::parse_case_pose(c["rough_pose"].get<std::string>());
    const auto loaded = hbos_test::load_screening_case(
        (fs::path(dir) / c["dir"].get<std::string>()).string(), pose);
    if (c.contains("pairs") &&
        c["pairs"].get<long long>() != static_cast<long long>(loaded.pairs.size())) {
      // A truncated pairs.csv would otherwise be measured as a smaller case.
      throw hbos::InvalidArgument(
          fmt::format("case '{}': the manifest lists {} pairs, {}/pairs.csv has {}",
                      c["name"].get<std::string>(), c["pairs"].get<long long>(),
                      (fs::path(dir) / c["dir"].get<std::string>()).string(), loaded.pairs.size()));
    }
    CaseMetrics m = hbos::cases::measure_case(loaded, strategies);
    hbos::cases::measure_equal_loss(loaded, strategies, m);
    m.disagreement = hbos_test::static_disagreement(loaded);
    m.name = c["name"].get<std::string>();
    m.scene = c["dir"].get<std::string>();
    m.rough_pose = c["rough_pose"].get<std::string>();
    m.static_sequence = c["people"].empty();
    all.push_back(std::move(m));
  }
  hbos::examples::write_file_atomically(markdown_path,
                                        markdown(all, manifest["cases"], strategies));
  if (!json_path.empty())
    hbos::examples::write_file_atomically(json_path, to_json(all, strategies).dump(1) + "\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return hbos::examples::run_tool("hbos-screening-eval", [&] { return run(argc, argv); });
}
