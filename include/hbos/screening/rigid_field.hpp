#pragma once
/// \file
/// The residual field of a small rigid motion, fitted to a frame's matches.
///
/// A pose error moves every static match's prediction as a small rigid motion of the scene
/// would: by J(p, q) xi, with J the pinhole's motion_jacobian at the predicted pixel p and inverse
/// depth q, and xi = (t, w) six numbers. An affine field in p approximates that shift, and it
/// also takes up image structure no pose error gives. After a refinement, that structure is what
/// a field fits on real frames (docs/results.md, "A field only a camera motion can give"), and
/// centring it away keeps the matches the rigid refinement cannot agree with. The rigid field
/// fits the pose-like part only.
///
/// Threading: re-entrant; the fit writes only its arguments.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "hbos/screening/matches.hpp"
#include "hbos/screening/pinhole.hpp"
#include "hbos/screening/residual_field.hpp"

namespace hbos::detail {

/// The rigid field of the matches with `use(i)`: up to max(iterations, 1) weighted least-squares
/// fits of J(p_i, q_i) xi to their residuals, each weighted by 1/sigma^2 and taken over those
/// within `window` whitened pixels of the current field. `start` is the field the first fit's
/// window is measured from (the screen passes the affine field it fitted on the same matches).
/// Fewer than 6 supporting matches, or a motion the supporting matches do not determine (all
/// at one pixel, say), leaves `start` as the result. Sums and the solve run in double.
/// `inside` is scratch.
template <class Scalar, class Use>
ResidualField<Scalar> fit_rigid_field(const Matches<Scalar>& matches, const Use& use,
                                      const ResidualField<Scalar>& start,
                                      const PinholeCamera<double>& camera, double window,
                                      int iterations, std::vector<std::uint8_t>& inside) {
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  const Eigen::Index n = matches.size();
  const double window2 = window * window;
  const auto jacobian = [&](Eigen::Index i, Vec6& ju, Vec6& jv) {
    const Eigen::Matrix<Scalar, 2, 1> p = matches.predicted(i);
    camera.motion_jacobian(Eigen::Vector2d(static_cast<double>(p.x()), static_cast<double>(p.y())),
                           static_cast<double>(inverse_depth_of(matches.depth(i))), ju, jv);
  };
  inside.assign(static_cast<std::size_t>(n), 0);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!use(i)) continue;
    const Eigen::Matrix<Scalar, 2, 1> e =
        matches.residual(i) - start.at(matches.predicted(i), inverse_depth_of(matches.depth(i)));
    inside[static_cast<std::size_t>(i)] =
        static_cast<double>(e.squaredNorm() * matches.information(i)) <= window2 ? 1 : 0;
  }
  Vec6 motion = Vec6::Zero();
  bool fitted = false;
  for (int it = 0; it < std::max(iterations, 1); ++it) {
    Mat6 a = Mat6::Zero();
    Vec6 b = Vec6::Zero();
    Eigen::Index support = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (inside[static_cast<std::size_t>(i)] == 0) continue;
      Vec6 ju, jv;
      jacobian(i, ju, jv);
      const double w = static_cast<double>(matches.information(i));
      const Eigen::Matrix<Scalar, 2, 1> r = matches.residual(i);
      a.noalias() += w * (ju * ju.transpose() + jv * jv.transpose());
      b.noalias() += w * (ju * static_cast<double>(r.x()) + jv * static_cast<double>(r.y()));
      ++support;
    }
    if (support < 6) break;
    const Eigen::LDLT<Mat6> ldlt(a);
    // A motion the samples do not pin down (too few distinct pixels, no depth spread for a
    // translation along the axis) would extrapolate wildly: keep what we have.
    if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > 1e-9)) break;
    const Vec6 next = ldlt.solve(b);
    if (!next.allFinite()) break;
    const bool converged = fitted && (next - motion).norm() < 1e-9;
    motion = next;
    fitted = true;
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (!use(i)) continue;
      Vec6 ju, jv;
      jacobian(i, ju, jv);
      const Eigen::Matrix<Scalar, 2, 1> r = matches.residual(i);
      const double ex = static_cast<double>(r.x()) - ju.dot(motion);
      const double ey = static_cast<double>(r.y()) - jv.dot(motion);
      inside[k] = (ex * ex + ey * ey) * static_cast<double>(matches.information(i)) <= window2;
    }
    if (converged) break;
  }
  if (!fitted) return start;
  ResidualField<Scalar> field;
  field.rigid = true;
  field.motion = motion.cast<Scalar>();
  field.camera.fx = static_cast<Scalar>(camera.fx);
  field.camera.fy = static_cast<Scalar>(camera.fy);
  field.camera.cx = static_cast<Scalar>(camera.cx);
  field.camera.cy = static_cast<Scalar>(camera.cy);
  return field;
}

}  // namespace hbos::detail
