#pragma once
/// \file
/// The study's pass/fail criteria, so that a regression in accuracy fails a test.

#include <optional>
#include <string>
#include <vector>

#include "study.hpp"

namespace hbos::study {

/// What to hold a run to; every unset part is skipped.
struct Targets {
  /// Per-set AUCs of a reference run (format_csv's layout): every method and data set of the
  /// reference must be present in the run and agree within `tolerance`.
  std::string expected_csv;
  /// PyOD's own AUCs (`dataset,...,roc_auc_default,...`): the PyOD mode must agree within
  /// `tolerance` on the data sets listed there.
  std::string pyod_reference_csv;
  /// PyOD's published mean over the run's data sets (0.7896 on the 17 ODDS sets), given to four
  /// decimals: the PyOD mode's mean must round to it.
  std::optional<double> published_pyod_mean;
  /// The default mode's mean must be at least the PyOD mode's, its AUCs unchanged by rescaling
  /// with powers of two (|change| < 1e-12), and the PyOD mode's changed by it on some set
  /// (> 1e-3: the rescaling bites).
  bool invariants = false;
  /// The run covers a chosen subset of the data sets: data sets of `expected_csv` and
  /// `pyod_reference_csv` that were not run are skipped instead of failing.
  bool subset = false;
  double tolerance = 1e-9;
};

/// Every failed criterion, as one message each; empty when the run meets all targets.
/// \throws std::runtime_error when a reference file cannot be read or is malformed.
[[nodiscard]] std::vector<std::string> check_targets(const StudyResult& result,
                                                     const Targets& targets);

}  // namespace hbos::study
