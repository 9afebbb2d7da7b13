#pragma once
/// \file
/// What one labelled residual case is (persons and their motion, mask, rough pose, seed), and the
/// two grids: the fixture the screen is designed on and the disjoint hold-out used only for the
/// final acceptance table.

#include "moving_person.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace hbos::cases {

/// The dynamic-object mask the feature extractor avoids (as the front end's extraction does).
enum class MaskKind {
  kNone,      ///< no mask
  kDegraded,  ///< the exact mask eroded, its lower part unmasked, missing in some frames
  kExact,     ///< the composited silhouette itself
};

/// The pose the residuals are measured under. Every scene carries both: a case is a scene and
/// one of them.
enum class RoughPoseKind {
  kRansac,     ///< cv::solvePnPRansac on the frame-to-frame matches (the front end's settings)
  kPerturbed,  ///< ground truth moved by exactly perturb_deg about / perturb_m along random axes
};

[[nodiscard]] const char* to_string(MaskKind kind);
[[nodiscard]] const char* to_string(RoughPoseKind kind);

/// How the degraded mask fails (the front end's MaskConfig fields of the same names).
struct Degradation {
  int erosion_px = 6;           ///< [px] erosion radius: the silhouette's edges leak
  double unmasked_lower = 0.4;  ///< share of the person's height left unmasked at the bottom
  int missing_every = 5;        ///< frames with index % N == N - 1 have no mask; 0 = never
};

/// One scene: the frames with its people composited and its mask. Its pair files hold the
/// predictions under both rough poses, so one scene gives two cases (`<name>_ransac`,
/// `<name>_pgt`).
struct CaseSpec {
  std::string name;                  ///< folder name
  std::string speed;                 ///< label: static, slow, medium, walk, mixed
  std::vector<PersonMotion> people;  ///< empty = the static case
  MaskKind mask = MaskKind::kNone;
  Degradation degradation;
  std::uint64_t seed = 0;    ///< of the perturbation (kPerturbed)
  double perturb_deg = 0.2;  ///< [deg] rotation of the perturbed ground truth
  double perturb_m = 0.003;  ///< [m] translation of the perturbed ground truth
  bool reverse = false;      ///< play the frames backwards (pairs (i+1 -> i)): other pairs
};

/// The fixture grid of scenes (tests/data/screening_cases).
[[nodiscard]] std::vector<CaseSpec> fixture_grid();
/// The hold-out grid of scenes (tests/data/screening_cases_holdout): other
/// people/speeds/seeds/pairs.
[[nodiscard]] std::vector<CaseSpec> holdout_grid();
/// The static scene alone, played forwards and backwards: no people, so it needs no more of a
/// sequence than its frames, ground truth and camera (for sequences other than fr1/xyz).
[[nodiscard]] std::vector<CaseSpec> static_grid();

}  // namespace hbos::cases
