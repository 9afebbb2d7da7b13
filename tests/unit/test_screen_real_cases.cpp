// The default screen against ORB-SLAM2's chi^2 gate and the 0.8 quantile on the labelled real
// residual cases (real TUM fr1/xyz frames with real people composited in, tests/data/
// screening_cases; the held-out set, screening_cases_holdout, was not looked at while the
// screen was designed). The full tables are in docs/screening.md; these tests pin what holds.

#include <catch2/catch.hpp>

#include <hbos/screening.hpp>

#include <string>
#include <vector>

#include "../support/equal_loss.hpp"
#include "../support/screening_cases.hpp"
#include "../support/static_disagreement.hpp"

namespace {

struct Counts {
  double static_dropped = 0, statics = 0, dynamic_kept = 0, dynamics = 0;
  [[nodiscard]] double static_loss() const { return static_dropped / statics; }
  [[nodiscard]] double dynamic_survival() const {
    return dynamics > 0 ? dynamic_kept / dynamics : 0;
  }
};

Counts screen_case(const hbos_test::ScreeningCase& c, const hbos::ScreenStrategy& strategy) {
  hbos::ReprojectionScreend screen(strategy);
  Counts k;
  for (const hbos_test::CasePair& pair : c.pairs) {
    const auto& r = screen.screen(pair.matches);
    for (Eigen::Index i = 0; i < pair.size(); ++i) {
      const auto u = static_cast<std::size_t>(i);
      if (pair.dynamic[u] != 0) {
        k.dynamics += 1;
        k.dynamic_kept += r.inlier(i) ? 1 : 0;
      } else if (pair.gross[u] == 0) {
        k.statics += 1;
        k.static_dropped += r.inlier(i) ? 0 : 1;
      }
    }
  }
  return k;
}

void check_collection(const std::string& root) {
  for (const hbos_test::CasePose pose :
       {hbos_test::CasePose::Ransac, hbos_test::CasePose::PerturbedGt}) {
    Counts pooled_default, pooled_chi2;
    for (const std::string& folder : hbos_test::list_case_folders(root)) {
      const hbos_test::ScreeningCase c = hbos_test::load_screening_case(folder, pose);
      const Counts d = screen_case(c, hbos::HbosScreen{});
      const Counts chi2 = screen_case(c, hbos::ChiSquareGate{});
      INFO(folder << (pose == hbos_test::CasePose::Ransac ? " (RANSAC)" : " (perturbed GT)")
                  << ": static loss default " << d.static_loss() << ", chi2 " << chi2.static_loss()
                  << "; dynamic kept default " << d.dynamic_survival() << ", chi2 "
                  << chi2.dynamic_survival());
      // No case costs the default more than a point of statics over chi^2 (measured: at most
      // +0.9 under RANSAC; under a perturbed pose chi^2 loses 9-20 % and the default under 5 %).
      // Matches near the mask carry the on-mask flag, as in hbos-screening-eval's tables.
      CHECK(d.static_loss() <= chi2.static_loss() + 0.01);
      if (c.is_static() && pose == hbos_test::CasePose::Ransac)
        CHECK(std::abs(d.static_loss() - chi2.static_loss()) <= 0.005);
      if (pose == hbos_test::CasePose::PerturbedGt) CHECK(d.static_loss() < chi2.static_loss());
      pooled_default.static_dropped += d.static_dropped;
      pooled_default.statics += d.statics;
      pooled_default.dynamic_kept += d.dynamic_kept;
      pooled_default.dynamics += d.dynamics;
      pooled_chi2.dynamic_kept += chi2.dynamic_kept;
      pooled_chi2.dynamics += chi2.dynamics;
    }
    // Under RANSAC (chi^2 at the same static loss) the default keeps fewer dynamic matches over
    // the collection; per case it does not everywhere (docs/screening.md names the cases).
    if (pose == hbos_test::CasePose::Ransac)
      CHECK(pooled_default.dynamic_survival() < pooled_chi2.dynamic_survival() - 0.03);
  }
}

// Every baseline swept to the default's static loss (tests/support/equal_loss.hpp; the sweep sees
// the labels, so it favours the baseline) keeps at least as many dynamic matches as the default,
// within half a point, in every case with a person; over the collection the chi^2 gate so tuned
// keeps clearly more. With the outlier history a tracker with memory passes in (pairs in order),
// the default keeps clearly fewer dynamics than without, and strictly fewer than every baseline
// swept to its (higher) static loss.
void check_equal_loss(const std::string& root) {
  for (const hbos_test::CasePose pose :
       {hbos_test::CasePose::Ransac, hbos_test::CasePose::PerturbedGt}) {
    long long default_kept = 0, chi2_kept = 0, dynamics = 0, history_kept = 0;
    for (const std::string& folder : hbos_test::list_case_folders(root)) {
      const hbos_test::ScreeningCase c = hbos_test::load_screening_case(folder, pose);
      if (c.is_static()) continue;
      hbos::ReprojectionScreend screen(hbos::HbosScreen{});
      const hbos_test::CaseTally d = hbos_test::tally_case(c, screen);
      for (const hbos_test::GateSetting& g : hbos_test::gate_settings()) {
        const hbos_test::AtStaticLoss at = hbos_test::at_static_loss(c, g, d.static_dropped_pct());
        INFO(folder << (pose == hbos_test::CasePose::Ransac ? " (RANSAC)" : " (perturbed GT)")
                    << ": " << g.screen << " at " << g.setting << " " << at.value << " loses "
                    << at.tally.static_dropped_pct() << " % of statics (default "
                    << d.static_dropped_pct() << " %) and keeps " << at.tally.dynamic_kept_pct()
                    << " % of dynamics (default " << d.dynamic_kept_pct() << " %)");
        REQUIRE(at.tally.static_dropped_pct() <= d.static_dropped_pct());
        CHECK(d.dynamic_kept_pct() <= at.tally.dynamic_kept_pct() + 0.5);
        if (g.screen == "chi2") chi2_kept += at.tally.dynamic_kept;
      }
      hbos::ReprojectionScreend with_memory(hbos::HbosScreen{});
      const hbos_test::CaseTally h = hbos_test::tally_case_with_history(c, with_memory);
      CHECK(h.static_dropped_pct() <= d.static_dropped_pct() + 5.0);
      for (const hbos_test::GateSetting& g : hbos_test::gate_settings()) {
        const hbos_test::AtStaticLoss at = hbos_test::at_static_loss(c, g, h.static_dropped_pct());
        INFO(folder << ", with history: " << g.screen << " at " << at.value << " keeps "
                    << at.tally.dynamic_kept_pct() << " % of dynamics at "
                    << at.tally.static_dropped_pct() << " % static loss; the default "
                    << h.dynamic_kept_pct() << " % at " << h.static_dropped_pct() << " %");
        CHECK(h.dynamic_kept_pct() < at.tally.dynamic_kept_pct());
      }
      default_kept += d.dynamic_kept;
      history_kept += h.dynamic_kept;
      dynamics += d.dynamics;
    }
    REQUIRE(dynamics > 0);
    CHECK(static_cast<double>(default_kept) <
          static_cast<double>(chi2_kept) - 0.03 * static_cast<double>(dynamics));
    CHECK(static_cast<double>(history_kept) <
          static_cast<double>(default_kept) - 0.05 * static_cast<double>(dynamics));
  }
}

// The statics the default rejects on evidence where chi^2 keeps them are not a random draw of
// the static matches: pooled over the cases with a person, under either rough pose, their
// residual under the reference pose is at least 1.8 times a typical static's (measured 2.1-2.7x),
// a share of them at least 4 times the statics' own lies within ORB's patch radius of the
// person (measured 5.2-11x), and they move with the person (their residual's median component
// along the nearest dynamic keypoint's exceeds that of every static beside the person).
void check_evidence_rejects(const std::string& root) {
  for (const hbos_test::CasePose pose :
       {hbos_test::CasePose::Ransac, hbos_test::CasePose::PerturbedGt}) {
    hbos_test::StaticDisagreement pooled;
    for (const std::string& folder : hbos_test::list_case_folders(root)) {
      const hbos_test::ScreeningCase c = hbos_test::load_screening_case(folder, pose);
      if (!c.is_static()) pooled += hbos_test::static_disagreement(c);
    }
    REQUIRE(pooled.only_default_by_evidence >= 100);
    REQUIRE(pooled.beside_person > 0);
    const double typical = hbos_test::median_of(pooled.all_reference);
    const double rejected = hbos_test::median_of(pooled.evidence_reference);
    const double share_beside =
        static_cast<double>(pooled.beside_person) / static_cast<double>(pooled.statics);
    const double rejected_beside = static_cast<double>(pooled.only_default_by_evidence_beside) /
                                   static_cast<double>(pooled.only_default_by_evidence);
    const double rejected_along = hbos_test::median_of(pooled.evidence_along_person);
    const double beside_along = hbos_test::median_of(pooled.beside_along_person);
    INFO(root << (pose == hbos_test::CasePose::Ransac ? " (RANSAC)" : " (perturbed GT)") << ": "
              << pooled.only_default_by_evidence
              << " statics rejected on evidence only, median reference residual " << rejected
              << " against " << typical << "; beside a person " << rejected_beside << " against "
              << share_beside << "; along the person " << rejected_along << " against "
              << beside_along);
    CHECK(rejected >= 1.8 * typical);
    CHECK(rejected_beside >= 4.0 * share_beside);
    CHECK(rejected_along > beside_along);
  }
}

}  // namespace

TEST_CASE(
    "real residual cases: the statics only the default's evidence rejects move with the "
    "person",
    "[screen_v2][real][evidence]") {
  check_evidence_rejects(std::string(HBOS_TEST_DATA_DIR) + "/screening_cases");
}

TEST_CASE(
    "held-out real residual cases: the statics only the default's evidence rejects move "
    "with the person",
    "[screen_v2][real][holdout][evidence]") {
  check_evidence_rejects(std::string(HBOS_TEST_DATA_DIR) + "/screening_cases_holdout");
}

TEST_CASE("real residual cases: at the default's static loss, no baseline keeps fewer dynamics",
          "[screen_v2][real][equal_loss]") {
  check_equal_loss(std::string(HBOS_TEST_DATA_DIR) + "/screening_cases");
}

TEST_CASE("held-out real residual cases: at the default's static loss, no baseline keeps fewer",
          "[screen_v2][real][holdout][equal_loss]") {
  check_equal_loss(std::string(HBOS_TEST_DATA_DIR) + "/screening_cases_holdout");
}

TEST_CASE(
    "real residual cases: the default loses no more statics than chi2 and keeps fewer "
    "dynamics over the collection",
    "[screen_v2][real]") {
  check_collection(std::string(HBOS_TEST_DATA_DIR) + "/screening_cases");
}

TEST_CASE("held-out real residual cases: the same holds on cases the design never saw",
          "[screen_v2][real][holdout]") {
  check_collection(std::string(HBOS_TEST_DATA_DIR) + "/screening_cases_holdout");
}
