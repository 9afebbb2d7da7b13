#pragma once
/// \file
/// What hbos-screening-eval measures on a labelled case: per strategy the share of static
/// matches dropped, dynamic matches kept and gross mismatches kept (single round per pair, pooled
/// over the case's pairs); per case how often the rough pose absorbed the person and the static
/// noise tail; and the acceptance rule of issue 7 item 7.

#include "equal_loss.hpp"
#include "eval_strategies.hpp"
#include "screening_cases.hpp"
#include "static_disagreement.hpp"

#include <string>
#include <vector>

namespace hbos::cases {

/// Counts of one strategy on one case (tests/support/equal_loss.hpp). Static = neither dynamic
/// nor gross; each percentage is NaN when there is no match of its kind.
using Tally = hbos_test::CaseTally;

/// A baseline swept to the default's static loss on a case (tests/support/equal_loss.hpp).
struct EqualLoss {
  std::string screen;                  ///< chi2, fixed, quantile or mad
  std::string setting;                 ///< what the swept value is
  hbos_test::AtStaticLoss at_default;  ///< at the default's static loss
  hbos_test::AtStaticLoss at_chi2;     ///< at chi2's (5.991) static loss
  /// at the static loss of the default screened with the caller's outlier history
  hbos_test::AtStaticLoss at_default_with_history;
};

/// chi2's 95 % gate on a 2-dof whitened residual [px/sigma]: sqrt(5.991).
inline constexpr double kChi2GatePx = 2.447;
/// Pairs with fewer dynamic matches do not count towards the absorbed share.
inline constexpr int kMinDynamicForAbsorbed = 10;

struct CaseMetrics {
  std::string name;              ///< the case (scene + rough pose)
  std::string scene;             ///< its folder
  std::string rough_pose;        ///< ransac | pgt | reference
  bool static_sequence = false;  ///< no person composited (the manifest's static scenes)
  int pairs = 0;
  long long matches = 0;
  std::vector<Tally> tallies;  ///< one per eval_strategies() entry, in that order
  /// Pairs with >= kMinDynamicForAbsorbed dynamic matches, and those among them whose median
  /// whitened dynamic residual under the rough pose is below kChi2GatePx (the pose absorbed it).
  int pairs_with_person = 0, pairs_absorbed = 0;
  /// Whitened |r| / sigma of the static matches under the rough pose [px/sigma].
  std::vector<double> static_whitened;
  /// The default with the outlier history a tracker with memory passes in (pairs screened in
  /// order; hbos_test::tally_case_with_history), and each baseline at equal static loss (both
  /// filled by measure_equal_loss).
  Tally default_with_history;
  std::vector<EqualLoss> equal_loss;
  /// The statics the default and chi2 disagree on, and their residuals under the reference pose
  /// (hbos_test::static_disagreement).
  hbos_test::StaticDisagreement disagreement;
};

/// Screens every pair of `c` with every strategy (single round) and counts.
[[nodiscard]] CaseMetrics measure_case(const hbos_test::ScreeningCase& c,
                                       const std::vector<NamedScreen>& strategies);

/// Screens `c` with the default and the caller's outlier history (m.default_with_history), then
/// sweeps each baseline of hbos_test::gate_settings() to the default's static loss with and
/// without that history and to chi2's static loss in `m` (which needs strategies named default
/// and chi2); the results go to m.equal_loss.
void measure_equal_loss(const hbos_test::ScreeningCase& c,
                        const std::vector<NamedScreen>& strategies, CaseMetrics& m);

/// The acceptance rule of one case (issue 7 item 7).
struct Verdict {
  bool pass = false;
  std::string reason;  ///< the failing comparisons with numbers, or what was checked
};

/// Static sequence: default's static loss <= chi2's + 0.5 points. Otherwise: default keeps fewer
/// dynamic matches than chi2 and than quantile, and drops no more statics than chi2 (cases
/// without dynamic matches, e.g. an exact mask: the static part only). Needs strategies named
/// default, chi2 and quantile.
[[nodiscard]] Verdict acceptance(const CaseMetrics& m, const std::vector<NamedScreen>& strategies);
/// The same rule for the default screened with the caller's outlier history
/// (m.default_with_history) in place of the default's single-pair counts.
[[nodiscard]] Verdict acceptance_with_history(const CaseMetrics& m,
                                              const std::vector<NamedScreen>& strategies);

/// The q-quantile (0..1) of `values` (sorted copy, linear interpolation); NaN when empty.
[[nodiscard]] double quantile_of(std::vector<double> values, double q);

}  // namespace hbos::cases
