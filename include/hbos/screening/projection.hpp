#pragma once
/// \file
/// Conveniences for callers that hold 3-D map points, a pose and pinhole intrinsics rather than
/// predicted pixels: filling the matches, and the rounds of ORB-SLAM2's pose optimisation.
///
/// Where it goes in an ORB-SLAM2-style tracker: after the rough pose (motion model or reference
/// keyframe), before Optimizer::PoseOptimization; see docs/screening.md for the snippet.
///
///     hbos::ReprojectionScreend screen;                // once; the recommended default
///     hbos::Matchesd matches;                          // once; reused every frame
///     ...per frame:
///     matches.clear();
///     for (each match i) matches.add(predicted_i, keypoint_i, hbos::sigma_from_octave(octave_i));
///     const auto& result = screen.screen(matches);
///     for (each match i) if (!result.inlier(i)) mark_outlier(i);
///
/// Threading: see screen.hpp; the free functions here are re-entrant.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <optional>

#include "hbos/error.hpp"
#include "hbos/screening/pinhole.hpp"
#include "hbos/screening/pose_refinement.hpp"
#include "hbos/screening/residual_field.hpp"
#include "hbos/screening/screen.hpp"
#include "hbos/screening/strategies.hpp"

namespace hbos {

/// Fills `matches` (cleared first) with the map points `points_world` (3 x n [m]) projected by
/// `T_cur_world` through `camera` as predictions, the keypoints `observed` (2 x n [px]), their
/// scale sigmas `sigma` (n) and prior flags `on_dynamic_mask` (n).
/// \throws InvalidArgument on mismatched sizes or a point at or behind the camera (depth <= 0).
template <class Scalar, class DerivedPoints, class DerivedObserved, class DerivedSigma,
          class DerivedMask>
void project_matches(const Eigen::MatrixBase<DerivedPoints>& points_world,
                     const Eigen::MatrixBase<DerivedObserved>& observed,
                     const Eigen::DenseBase<DerivedSigma>& sigma,
                     const Eigen::DenseBase<DerivedMask>& on_dynamic_mask,
                     const Eigen::Transform<Scalar, 3, Eigen::Isometry>& T_cur_world,
                     const PinholeCamera<Scalar>& camera, Matches<Scalar>& matches) {
  detail::validate(camera);
  const Eigen::Index n = points_world.cols();
  detail::require(points_world.rows() == 3, "points_world must be 3 x n, got ", points_world.rows(),
                  " rows");
  detail::require(observed.rows() == 2 && observed.cols() == n, "observed must be 2 x ", n,
                  ", got ", observed.rows(), " x ", observed.cols());
  detail::require(sigma.size() == n, "sigma has ", sigma.size(), " entries for ", n, " points");
  detail::require(on_dynamic_mask.size() == n, "on_dynamic_mask has ", on_dynamic_mask.size(),
                  " entries for ", n, " points");
  matches.clear();
  matches.reserve(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Matrix<Scalar, 3, 1> p_c =
        T_cur_world * Eigen::Matrix<Scalar, 3, 1>(points_world.col(i));
    detail::require(p_c.z() > Scalar(0), "point ", i, " is at or behind the camera (depth ",
                    p_c.z(), " m)");
    matches.add(camera.project(p_c), Eigen::Matrix<Scalar, 2, 1>(observed.col(i)),
                static_cast<Scalar>(sigma.derived().coeff(i)),
                static_cast<bool>(on_dynamic_mask.derived().coeff(i)));
    matches.set_depth(i, p_c.z());
  }
}

/// project_matches with sigma 1 and no prior flags.
template <class Scalar, class DerivedPoints, class DerivedObserved>
void project_matches(const Eigen::MatrixBase<DerivedPoints>& points_world,
                     const Eigen::MatrixBase<DerivedObserved>& observed,
                     const Eigen::Transform<Scalar, 3, Eigen::Isometry>& T_cur_world,
                     const PinholeCamera<Scalar>& camera, Matches<Scalar>& matches) {
  const Eigen::Index n = points_world.cols();
  project_matches(points_world, observed, Eigen::Array<Scalar, Eigen::Dynamic, 1>::Ones(n),
                  Eigen::Array<bool, Eigen::Dynamic, 1>::Zero(n), T_cur_world, camera, matches);
}

/// Options of screen_and_refine_pose.
struct IteratedScreenOptions {
  int rounds = 4;  ///< screenings in all (ORB-SLAM2's PoseOptimization runs 4 rounds), >= 1
  Eigen::Index min_inliers = 10;  ///< stop refitting below this many inliers (ORB-SLAM2: 10), >= 3
  PoseRefinementOptions refinement{};  ///< the Gauss-Newton refit on each round's inliers
  /// [px/sigma] the noise gate's floor (NoiseGate::floor) in the rounds after the first, for
  /// strategies with a noise gate; 0 = the screen's own floor in every round, as ORB-SLAM2 keeps
  /// one chi^2 gate. The first round judges the rough pose, whose error the residual field may
  /// not absorb; the later ones a pose refined on the survivors, where the gate can follow the
  /// frame's own noise further down. The SLAM example's frame tracker gates its later rounds at 3
  /// noise scales with no floor of their own; its map tracker keeps one floor (docs/results.md,
  /// "The noise gate after the first refinement"). >= 0.
  double later_gate_floor = 0.0;
  /// In the rounds after the first, the default screen refits its field as the pixel shift of a
  /// small rigid motion (RefitModel::Rigid, with `camera` and the points' depths) instead of an
  /// affine field: after a refinement, an affine field also fits structure no pose error gives,
  /// and centring that away keeps the matches the refinement cannot agree with. The SLAM
  /// example's trackers do (docs/results.md, "A field only a camera motion can give").
  bool later_rigid_field = false;
};

/// The rounds of ORB-SLAM2's PoseOptimization, written out for callers that hold 3-D points:
/// screen -> refine the pose on the inliers -> re-project -> re-screen, `options.rounds`
/// screenings (fewer when the inliers drop below `options.min_inliers`). `matches` must hold
/// the projections of `points_world` (3 x n [m]) under `T_cur_world`, e.g. from project_matches;
/// on return both are updated to the refined pose, and the result is the last screen's. Every
/// round screens all matches again, so a match rejected under the rough pose can come back.
/// A caller with its own optimiser writes the same loop around its own refit (the SLAM example's
/// tracker does).
template <class Scalar, class DerivedPoints>
const ScreenResult<Scalar>& screen_and_refine_pose(
    ReprojectionScreen<Scalar>& screen, const Eigen::MatrixBase<DerivedPoints>& points_world,
    const PinholeCamera<Scalar>& camera, Eigen::Transform<Scalar, 3, Eigen::Isometry>& T_cur_world,
    Matches<Scalar>& matches, const IteratedScreenOptions& options = {}) {
  detail::require(points_world.rows() == 3 && points_world.cols() == matches.size(),
                  "points_world must be 3 x ", matches.size(), ", got ", points_world.rows(), " x ",
                  points_world.cols());
  detail::require(options.rounds >= 1, "IteratedScreenOptions rounds must be >= 1, got ",
                  options.rounds);
  detail::require(options.min_inliers >= 3, "IteratedScreenOptions min_inliers must be >= 3, got ",
                  options.min_inliers);
  using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
  // The later rounds' config, where it differs; the caller's config is back in place on return,
  // a throw included.
  const ScreenConfig first = screen.config();
  LaterRounds later_rounds{options.later_gate_floor, std::nullopt};
  if (options.later_rigid_field) later_rounds.rigid_field = camera.template cast<double>();
  const std::optional<ScreenConfig> later = later_rounds_config(first, later_rounds);
  const bool switch_config = later.has_value();
  // (The caller's config was validated when it was set, so putting it back cannot throw.)
  const auto restore = [&] {
    if (switch_config) screen.set_config(first);
  };
  try {
    for (int round = 1;; ++round) {
      if (switch_config) screen.set_config(round == 1 ? first : *later);
      const ScreenResult<Scalar>& result = screen.screen(matches);
      if (round == options.rounds || result.n_inliers() < options.min_inliers) {
        restore();  // the result stays valid: set_config keeps the screen's buffers
        return result;
      }
      refine_pose(
          matches.size(), [&](Eigen::Index i) { return Vec3(points_world.col(i)); },
          [&](Eigen::Index i) { return matches.observed(i); },
          [&](Eigen::Index i) { return matches.sigma(i); },
          [&](Eigen::Index i) { return result.inlier(i); }, camera, T_cur_world,
          options.refinement);
      for (Eigen::Index i = 0; i < matches.size(); ++i) {
        const Vec3 p_c = T_cur_world * Vec3(points_world.col(i));
        // A point pushed behind the camera by the refit keeps its old prediction.
        if (p_c.z() > Scalar(0)) {
          matches.set_predicted(i, camera.project(p_c));
          matches.set_depth(i, p_c.z());
        }
      }
    }
  } catch (...) {
    restore();
    throw;
  }
}

}  // namespace hbos
