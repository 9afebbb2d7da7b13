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

/// Scratch of fit_rigid_field, reused across frames.
struct RigidFitWork {
  std::vector<double> rows;          // per fitted match: ju (6), jv (6), rx, ry, 1/sigma^2
  std::vector<std::uint8_t> inside;  // per fitted match: within the window of the current fit
  void reserve(std::size_t n) {
    rows.reserve(n * kRowSize);
    inside.reserve(n);
  }
  static constexpr std::size_t kRowSize = 15;
};

/// The rigid field of the matches with `use(i)`: up to max(iterations, 1) weighted least-squares
/// fits of J(p_i, q_i) xi to their residuals, each weighted by 1/sigma^2 and taken over those
/// within `window` whitened pixels of the current field. `start` is the field the first fit's
/// window is measured from (the screen passes the affine field it fitted on the same matches).
/// Fewer than 6 supporting matches, or a motion the supporting matches do not determine (all
/// at one pixel, say), leaves `start` as the result. Sums and the solve run in double; each
/// match's Jacobian is formed once.
template <class Scalar, class Use>
ResidualField<Scalar> fit_rigid_field(const Matches<Scalar>& matches, const Use& use,
                                      const ResidualField<Scalar>& start,
                                      const PinholeCamera<double>& camera, double window,
                                      int iterations, RigidFitWork& work) {
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  constexpr std::size_t kRow = RigidFitWork::kRowSize;
  const double window2 = window * window;
  std::vector<double>& rows = work.rows;
  std::vector<std::uint8_t>& inside = work.inside;
  rows.clear();
  inside.clear();
  for (Eigen::Index i = 0; i < matches.size(); ++i) {
    if (!use(i)) continue;
    const Eigen::Matrix<Scalar, 2, 1> p = matches.predicted(i);
    const Scalar q = inverse_depth_of(matches.depth(i));
    Vec6 ju, jv;
    camera.motion_jacobian(Eigen::Vector2d(static_cast<double>(p.x()), static_cast<double>(p.y())),
                           static_cast<double>(q), ju, jv);
    const Eigen::Matrix<Scalar, 2, 1> r = matches.residual(i);
    const double w = static_cast<double>(matches.information(i));
    rows.insert(rows.end(), ju.data(), ju.data() + 6);
    rows.insert(rows.end(), jv.data(), jv.data() + 6);
    rows.push_back(static_cast<double>(r.x()));
    rows.push_back(static_cast<double>(r.y()));
    rows.push_back(w);
    const Eigen::Matrix<Scalar, 2, 1> e = r - start.at(p, q);
    inside.push_back(static_cast<double>(e.squaredNorm() * matches.information(i)) <= window2 ? 1
                                                                                              : 0);
  }
  const std::size_t m = inside.size();
  Vec6 motion = Vec6::Zero();
  bool fitted = false;
  for (int it = 0; it < std::max(iterations, 1); ++it) {
    // The normal equations' lower triangle (all the solve reads), each entry summed as
    // w (ju_a ju_b + jv_a jv_b).
    Mat6 a = Mat6::Zero();
    Vec6 b = Vec6::Zero();
    std::size_t support = 0;
    for (std::size_t k = 0; k < m; ++k) {
      if (inside[k] == 0) continue;
      const double* row = rows.data() + k * kRow;
      const double* ju = row;
      const double* jv = row + 6;
      const double rx = row[12], ry = row[13], w = row[14];
      for (int c = 0; c < 6; ++c)
        for (int r = c; r < 6; ++r) a(r, c) += w * (ju[r] * ju[c] + jv[r] * jv[c]);
      for (int r = 0; r < 6; ++r) b(r) += w * (ju[r] * rx + jv[r] * ry);
      ++support;
    }
    if (support < 6) break;
    const Eigen::LDLT<Mat6, Eigen::Lower> ldlt(a);
    // A motion the samples do not pin down (too few distinct pixels, no depth spread for a
    // translation along the axis) would extrapolate wildly: keep what we have.
    if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > 1e-9)) break;
    const Vec6 next = ldlt.solve(b);
    if (!next.allFinite()) break;
    const bool converged = fitted && (next - motion).norm() < 1e-9;
    motion = next;
    fitted = true;
    // The same support as this fit's gives the same motion again: stop (what one more
    // iteration would return, without the pass).
    bool moved = false;
    for (std::size_t k = 0; k < m; ++k) {
      const double* row = rows.data() + k * kRow;
      const Vec6 ju = Eigen::Map<const Vec6>(row), jv = Eigen::Map<const Vec6>(row + 6);
      const double ex = row[12] - ju.dot(motion);
      const double ey = row[13] - jv.dot(motion);
      const std::uint8_t now = (ex * ex + ey * ey) * row[14] <= window2 ? 1 : 0;
      moved = moved || now != inside[k];
      inside[k] = now;
    }
    if (converged || !moved) break;
  }
  if (!fitted) return start;
  ResidualField<Scalar> field;
  field.rigid = true;
  field.motion = motion.cast<Scalar>();
  field.camera = camera.cast<Scalar>();
  return field;
}

}  // namespace hbos::detail
