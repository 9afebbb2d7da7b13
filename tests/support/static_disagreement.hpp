#pragma once
/// \file
/// Where the default screen and ORB-SLAM2's chi^2 gate disagree about the static matches of a
/// labelled real case (tests/data/screening_cases), and what those matches are under the
/// reference pose. "Static" is the labels' own: neither keypoint on a composited person and a
/// reference residual within 3 sigma (not gross). A keypoint just outside a person's silhouette
/// is static by that label, but its corner and descriptor patch can hold the person's edge, which
/// moves with the person: such a match is static by label and dynamic in what it measures. The
/// reference residual (the ground truth refined on the static matches) tells the two apart
/// without any screen's help.

#include <hbos/screening.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "screening_cases.hpp"

namespace hbos_test {

/// [px] a keypoint this near a dynamic keypoint of the same frame lies beside the person: ORB's
/// patch radius at level 0, as the cases' `on_mask` flag uses for the mask.
inline constexpr double kBesidePersonPx = 15.0;

/// One case's static matches, split by which screen rejects them (single round per pair).
struct StaticDisagreement {
  long statics = 0;                   ///< static matches (neither dynamic nor gross)
  long beside_person = 0;             ///< of them, within kBesidePersonPx of a dynamic keypoint
  long only_default_by_gate = 0;      ///< rejected by the default beyond its gate, kept by chi^2
  long only_default_by_evidence = 0;  ///< rejected by the default inside its gate, kept by chi^2
  long only_default_by_evidence_beside = 0;  ///< of those, beside the person
  long only_chi2 = 0;                        ///< rejected by chi^2, kept by the default
  /// |r_ref| / sigma [px/sigma], the residual under the reference pose: of every static match,
  /// of those only the default's evidence rejects, and of those only chi^2 rejects
  std::vector<double> all_reference, evidence_reference, chi2_reference;
  /// The component of a match's reference residual along its nearest dynamic keypoint's
  /// reference residual [px/sigma] (how far it moves with the person): of the matches only the
  /// default's evidence rejects, and of every static match beside the person
  std::vector<double> evidence_along_person, beside_along_person;

  /// Pools another case's counts and samples into this one.
  StaticDisagreement& operator+=(const StaticDisagreement& o) {
    statics += o.statics;
    beside_person += o.beside_person;
    only_default_by_gate += o.only_default_by_gate;
    only_default_by_evidence += o.only_default_by_evidence;
    only_default_by_evidence_beside += o.only_default_by_evidence_beside;
    only_chi2 += o.only_chi2;
    for (auto [to, from] : {std::pair{&all_reference, &o.all_reference},
                            std::pair{&evidence_reference, &o.evidence_reference},
                            std::pair{&chi2_reference, &o.chi2_reference},
                            std::pair{&evidence_along_person, &o.evidence_along_person},
                            std::pair{&beside_along_person, &o.beside_along_person}})
      to->insert(to->end(), from->begin(), from->end());
    return *this;
  }
};

/// The median of `v` (NaN when empty); `v` is taken by value and reordered.
[[nodiscard]] inline double median_of(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

/// Screens every pair of `c` with `screen` (the default unless given; an HBOS screen with the
/// noise gate, so that its gate tells gate from evidence) and chi^2 (ChiSquareGate{}), one round
/// each, with the case's on-mask flags as loaded, and splits the static matches.
[[nodiscard]] inline StaticDisagreement static_disagreement(
    const ScreeningCase& c, const hbos::ScreenConfig& screen = hbos::ScreenConfig{}) {
  hbos::ReprojectionScreend by_default{screen};
  hbos::ReprojectionScreend by_chi2{hbos::ScreenConfig{hbos::ChiSquareGate{}}};
  StaticDisagreement out;
  std::vector<std::uint8_t> default_kept;
  std::vector<std::uint8_t> default_beyond_gate;
  for (const CasePair& pair : c.pairs) {
    const auto n = static_cast<std::size_t>(pair.size());
    const auto& d = by_default.screen(pair.matches);
    default_kept.assign(n, 0);
    default_beyond_gate.assign(n, 0);
    for (std::size_t k = 0; k < n; ++k) {
      const auto i = static_cast<Eigen::Index>(k);
      default_kept[k] = d.inlier(i) ? 1 : 0;
      default_beyond_gate[k] = d.magnitude(i) > d.magnitude_cut() ? 1 : 0;
    }
    const auto& x = by_chi2.screen(pair.matches);
    for (std::size_t k = 0; k < n; ++k) {
      if (pair.dynamic[k] != 0 || pair.gross[k] != 0) continue;
      const auto i = static_cast<Eigen::Index>(k);
      // The nearest dynamic keypoint of this frame, if any.
      double nearest = std::numeric_limits<double>::infinity();
      std::size_t person = n;
      for (std::size_t j = 0; j < n; ++j) {
        if (pair.dynamic[j] == 0) continue;
        const double distance =
            (pair.matches.observed(i) - pair.matches.observed(static_cast<Eigen::Index>(j))).norm();
        if (distance < nearest) {
          nearest = distance;
          person = j;
        }
      }
      const double sigma = pair.matches.sigma(i);
      const Eigen::Vector2d reference = pair.reference_residual.col(i);
      double along = 0.0;
      if (person < n) {
        const Eigen::Vector2d moves =
            pair.reference_residual.col(static_cast<Eigen::Index>(person));
        if (moves.norm() > 0.0) along = reference.dot(moves.normalized()) / sigma;
      }
      const bool beside = nearest <= kBesidePersonPx;
      ++out.statics;
      out.all_reference.push_back(reference.norm() / sigma);
      if (beside) {
        ++out.beside_person;
        out.beside_along_person.push_back(along);
      }
      const bool kept_by_default = default_kept[k] != 0, kept_by_chi2 = x.inlier(i);
      if (!kept_by_default && kept_by_chi2) {
        if (default_beyond_gate[k] != 0) {
          ++out.only_default_by_gate;
        } else {
          ++out.only_default_by_evidence;
          out.only_default_by_evidence_beside += beside ? 1 : 0;
          out.evidence_reference.push_back(reference.norm() / sigma);
          out.evidence_along_person.push_back(along);
        }
      } else if (kept_by_default && !kept_by_chi2) {
        ++out.only_chi2;
        out.chi2_reference.push_back(reference.norm() / sigma);
      }
    }
  }
  return out;
}

}  // namespace hbos_test
