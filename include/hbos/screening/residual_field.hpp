#pragma once
/// \file
/// The dominant residual field of a frame's matches and the residual features built on it.
///
/// Features the screen derives from the residuals (screen.hpp):
/// - magnitude m_i = |r_i - c(p_i)| / sigma_i (whitened) or |r_i - c(p_i)| (raw) [px/sigma or px];
/// - direction a_i = atan2 of r_i - c(p_i), a periodic angle in [-pi, pi) [rad].
///
/// c(p) is the dominant residual field (`ResidualCenter`): the coherent residual that the rough
/// pose's error gives every static match — constant (the mode of the residual vectors: a weighted
/// mean shift started at the coordinate-wise median) or affine in the predicted pixel p (it also
/// absorbs the roll and zoom of the pose error). Subtracting it is what lets a screen run *before*
/// pose optimisation. A rigid field (rigid_field.hpp) is the pixel shift of a small camera motion
/// itself: it needs the depths and the intrinsics, and it cannot absorb what no pose error gives.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "hbos/error.hpp"
#include "hbos/screening/matches.hpp"
#include "hbos/screening/pinhole.hpp"
#include "hbos/screening/pixel_grid.hpp"

namespace hbos {

/// The model of the coherent residual a rough pose gives the static matches.
enum class ResidualCenter {
  None,      ///< no centering: magnitudes are measured from zero
  Constant,  ///< one dominant residual c for the whole image (mean-shift mode)
  Affine     ///< c(p) = c + G (p - p0): also absorbs the roll and zoom a rough pose leaves
};

/// The dominant residual as a function of the predicted pixel p and the inverse depth q of the
/// predicted point: c(p, q) = offset + gradient (p - origin) + J(p, q) motion, where J is the
/// camera's motion_jacobian. The last term is the pixel shift a small rigid motion gives (a
/// rigid field, FieldFit::refit_model); it is zero unless `rigid`.
template <class Scalar>
struct ResidualField {
  Eigen::Matrix<Scalar, 2, 1> offset = Eigen::Matrix<Scalar, 2, 1>::Zero();    ///< [px]
  Eigen::Matrix<Scalar, 2, 2> gradient = Eigen::Matrix<Scalar, 2, 2>::Zero();  ///< [px/px]
  Eigen::Matrix<Scalar, 2, 1> origin = Eigen::Matrix<Scalar, 2, 1>::Zero();    ///< [px]
  /// A small rigid motion of the scene in the camera frame (t [m], w [rad]); read when `rigid`.
  Eigen::Matrix<Scalar, 6, 1> motion = Eigen::Matrix<Scalar, 6, 1>::Zero();
  PinholeCamera<Scalar> camera{};  ///< the intrinsics `motion` projects with
  bool rigid = false;
  /// c(p, q); q = 0 for a point of unknown depth (it moves as a point at infinity would).
  [[nodiscard]] Eigen::Matrix<Scalar, 2, 1> at(const Eigen::Matrix<Scalar, 2, 1>& p,
                                               Scalar inverse_depth = Scalar(0)) const {
    Eigen::Matrix<Scalar, 2, 1> c = affine_at(p);
    if (rigid) c += camera.pixel_motion(p, inverse_depth, motion);
    return c;
  }
  /// The affine part alone: c(p, q) of a field that is not `rigid`, without the branch (for
  /// loops over every match that decide the model once).
  [[nodiscard]] Eigen::Matrix<Scalar, 2, 1> affine_at(const Eigen::Matrix<Scalar, 2, 1>& p) const {
    return offset + gradient * (p - origin);
  }
};

/// The inverse depth a field is evaluated with: 1 / depth, or 0 where the depth is not known.
template <class Scalar>
[[nodiscard]] Scalar inverse_depth_of(Scalar depth_m) {
  return std::isfinite(depth_m) && depth_m > Scalar(0) ? Scalar(1) / depth_m : Scalar(0);
}

/// How the residual features are formed (see the file comment).
struct ResidualOptions {
  bool whiten = true;  ///< divide the magnitude by sigma_i (units px/sigma), as chi^2 does
  ResidualCenter center = ResidualCenter::Affine;  ///< what is subtracted before the magnitude
  double center_window = 3.0;  ///< [px/sigma] residuals within this of the field move it
  int center_iterations = 5;   ///< mean-shift / reweighting steps after the median start, >= 0
};

namespace detail {

inline void validate(const ResidualOptions& o) {
  require(std::isfinite(o.center_window) && o.center_window > 0.0,
          "ResidualOptions center_window must be finite and > 0, got ", o.center_window);
  require(o.center_iterations >= 0, "ResidualOptions center_iterations must be >= 0, got ",
          o.center_iterations);
}

/// The residual samples a field is fitted to, column-wise: predicted pixel (u, v) [px],
/// residual (rx, ry) [px] and information w = 1/sigma^2. Reused across frames.
template <class Scalar>
struct FieldSamples {
  std::vector<Scalar> u, v, rx, ry, w;
  mutable std::vector<std::pair<Scalar, Scalar>> sorted;  // scratch of the weighted median
  void clear() {
    for (auto* c : {&u, &v, &rx, &ry, &w}) c->clear();
  }
  void reserve(std::size_t n) {
    for (auto* c : {&u, &v, &rx, &ry, &w}) c->reserve(n);
    sorted.reserve(n);
  }
  [[nodiscard]] std::size_t size() const { return w.size(); }
};

/// Copies the matches with `use(i)` into `samples` (cleared first).
template <class Scalar, class Use>
void collect_field_samples(const Matches<Scalar>& matches, const Use& use,
                           FieldSamples<Scalar>& samples) {
  // Sized once and trimmed after: a push_back per column and sample kept a capacity check and a
  // size update in the loop.
  const auto n = static_cast<std::size_t>(matches.size());
  for (auto* c : {&samples.u, &samples.v, &samples.rx, &samples.ry, &samples.w}) c->resize(n);
  std::size_t m = 0;
  for (Eigen::Index i = 0; i < matches.size(); ++i) {
    if (!use(i)) continue;
    const Eigen::Matrix<Scalar, 2, 1> p = matches.predicted(i);
    const Eigen::Matrix<Scalar, 2, 1> r = matches.residual(i);
    samples.u[m] = p.x();
    samples.v[m] = p.y();
    samples.rx[m] = r.x();
    samples.ry[m] = r.y();
    // 1 / sigma^2 as Matches computed it when the match was added (the same division of the
    // same value): no division per sample and fit.
    samples.w[m] = matches.information(i);
    ++m;
  }
  for (auto* c : {&samples.u, &samples.v, &samples.rx, &samples.ry, &samples.w}) c->resize(m);
}

/// The most cells balance_by_cell uses (64 a side), so a workspace can reserve them.
inline constexpr std::size_t kMaxBalanceCells = std::size_t{64} * 64;

/// Caps the weight of crowded image cells: with the samples binned into square cells of
/// `cell_px` over their predicted pixels, a cell holding more than the average occupied cell's
/// count has its samples' weights scaled down to that count. A dynamic object crowding a few
/// cells then cannot outvote the background spread over the image. `counts`, `cell_of` and
/// `factor` are scratch.
template <class Scalar>
void balance_by_cell(FieldSamples<Scalar>& samples, double cell_px,
                     std::vector<std::uint32_t>& counts, std::vector<std::uint32_t>& cell_of,
                     std::vector<Scalar>& factor) {
  const std::size_t m = samples.size();
  if (m == 0 || !(cell_px > 0.0)) return;
  // The extremes as std::minmax_element finds them (the first smallest, the last largest), with
  // selects instead of its branches, which went either way for pixels in no particular order.
  Scalar u_lo = samples.u[0], u_hi = u_lo, v_lo = samples.v[0], v_hi = v_lo;
  for (std::size_t i = 1; i < m; ++i) {
    u_lo = std::min(u_lo, samples.u[i]);
    u_hi = std::max(samples.u[i], u_hi);
    v_lo = std::min(v_lo, samples.v[i]);
    v_hi = std::max(samples.v[i], v_hi);
  }
  // At most 64 x 64 cells (kMaxBalanceCells; larger cells for a larger spread).
  const PixelGrid grid(static_cast<double>(u_lo), static_cast<double>(u_hi),
                       static_cast<double>(v_lo), static_cast<double>(v_hi), cell_px, 64.0);
  counts.assign(grid.nx() * grid.ny(), 0);
  cell_of.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    cell_of[i] = static_cast<std::uint32_t>(
        grid.cell(static_cast<double>(samples.u[i]), static_cast<double>(samples.v[i])));
    ++counts[cell_of[i]];
  }
  std::size_t occupied = 0;
  for (const std::uint32_t c : counts) occupied += c > 0 ? 1 : 0;
  const double cap = static_cast<double>(m) / static_cast<double>(occupied);
  // The factor of each crowded cell once, not a division per sample (the same quotient: the
  // same bits). 1 marks a cell within the cap, whose samples keep their weight.
  factor.resize(counts.size());
  for (std::size_t c = 0; c < counts.size(); ++c) {
    const auto count = static_cast<double>(counts[c]);
    factor[c] = count > cap ? static_cast<Scalar>(cap / count) : Scalar(1);
  }
  // A factor of 1 leaves its weight as it is (w * 1 = w exactly): no branch.
  for (std::size_t i = 0; i < m; ++i) samples.w[i] *= factor[cell_of[i]];
}

/// The weighted median of (value, weight > 0) pairs: the smallest value whose cumulative weight,
/// in ascending order of value, reaches half the total (the largest when rounding leaves every
/// cumulative weight short of it). Reorders `pairs`. Expected O(n): a quickselect that carries
/// the weight of what it partitions, one three-way partition per step on the side that holds
/// the median (an nth_element per step, then a second pass for its weight, was a fifth of the
/// default screen's time).
template <class Scalar>
Scalar weighted_median(std::vector<std::pair<Scalar, Scalar>>& pairs) {
  Scalar total = 0;
  for (const auto& p : pairs) total += p.second;
  const Scalar half = total / Scalar(2);
  auto first = pairs.begin(), last = pairs.end();
  Scalar below = 0;  // the weight of every value before `first`, always short of half
  Scalar largest = first->first;
  while (last - first > 1) {
    // Median-of-three pivot, one of the range's values, so each step removes at least one.
    const Scalar a = first->first, b = (first + (last - first) / 2)->first, c = (last - 1)->first;
    const Scalar pivot = std::max(std::min(a, b), std::min(std::max(a, b), c));
    // [first, lt) < pivot, [lt, i) == pivot, [gt, last) > pivot.
    auto lt = first, i = first, gt = last;
    Scalar less = 0, equal = 0;
    while (i < gt) {
      if (i->first < pivot) {
        less += i->second;
        std::iter_swap(lt++, i++);
      } else if (pivot < i->first) {
        std::iter_swap(i, --gt);
      } else {
        equal += i->second;
        ++i;
      }
    }
    if (below + less >= half) {
      last = lt;  // reached among the smaller values (never empty: below alone is short)
    } else if (below + less + equal >= half) {
      return pivot;
    } else {
      below += less + equal;
      largest = pivot;
      first = gt;
    }
  }
  return first == last ? largest : first->first;
}

/// Where a dominant-residual fit starts (the weighted median of its samples), kept so that a
/// refit of the same samples with another window skips the selection.
template <class Scalar>
struct FieldStart {
  Eigen::Matrix<Scalar, 2, 1> value = Eigen::Matrix<Scalar, 2, 1>::Zero();
  bool valid = false;
  void reset() { valid = false; }
};

/// The start of a dominant-residual fit: the coordinate-wise median of the residuals, weighted
/// when the weights differ. At least one sample.
template <class Scalar>
Eigen::Matrix<Scalar, 2, 1> weighted_start(const FieldSamples<Scalar>& samples,
                                           std::vector<Scalar>& scratch) {
  const std::size_t m = samples.size();
  Eigen::Matrix<Scalar, 2, 1> c(0, 0);
  const bool weighted = std::adjacent_find(samples.w.begin(), samples.w.end(),
                                           std::not_equal_to<Scalar>()) != samples.w.end();
  for (int axis = 0; axis < 2; ++axis) {
    const std::vector<Scalar>& r = axis == 0 ? samples.rx : samples.ry;
    if (!weighted) {
      scratch.assign(r.begin(), r.end());
      const auto mid = scratch.begin() + static_cast<std::ptrdiff_t>(m / 2);
      std::nth_element(scratch.begin(), mid, scratch.end());
      c(axis) = *mid;
      continue;
    }
    // Unequal weights (cell balancing, sigma): the weighted median, so the start of the mean
    // shift is as hard to pull as the weights say.
    std::vector<std::pair<Scalar, Scalar>>& pairs = samples.sorted;
    pairs.resize(m);
    for (std::size_t i = 0; i < m; ++i) pairs[i] = {r[i], samples.w[i]};
    c(axis) = weighted_median(pairs);
  }
  return c;
}

/// The dominant residual of `samples`: the coordinate-wise median, then `iterations` steps of a
/// mean shift with a flat window of `window` whitened pixels, each residual weighted by its
/// information 1/sigma^2. (0, 0) without samples. `scratch` grows to the sample count.
/// With `start` valid, the fit starts from it; otherwise the median is stored there (when given).
template <class Scalar>
Eigen::Matrix<Scalar, 2, 1> dominant_residual(const FieldSamples<Scalar>& samples, double window,
                                              int iterations, std::vector<Scalar>& scratch,
                                              FieldStart<Scalar>* start = nullptr) {
  const std::size_t m = samples.size();
  Eigen::Matrix<Scalar, 2, 1> c(0, 0);
  if (m == 0) return c;
  if (start != nullptr && start->valid) {
    c = start->value;
  } else {
    c = weighted_start(samples, scratch);
    if (start != nullptr) {
      start->value = c;
      start->valid = true;
    }
  }
  const auto window2 = static_cast<Scalar>(window * window);
  for (int it = 0; it < iterations; ++it) {
    Scalar sx = 0, sy = 0, weight = 0;
    for (std::size_t i = 0; i < m; ++i) {
      const Scalar dx = samples.rx[i] - c.x(), dy = samples.ry[i] - c.y();
      // Inside the window when |d|^2 / sigma^2 <= window^2, i.e. |d|^2 w <= window^2.
      const Scalar in = (dx * dx + dy * dy) * samples.w[i] <= window2 ? samples.w[i] : Scalar(0);
      sx += in * samples.rx[i];
      sy += in * samples.ry[i];
      weight += in;
    }
    if (!(weight > Scalar(0))) break;
    const Eigen::Matrix<Scalar, 2, 1> next(sx / weight, sy / weight);
    const bool converged = (next - c).squaredNorm() < Scalar(1e-8);
    c = next;
    if (converged) break;
  }
  return c;
}

/// The residual field of `center` (see ResidualOptions): the constant mode, then for Affine up to
/// `iterations` reweighted least-squares fits of c + G (p - p0) to the samples within `window`
/// whitened pixels of the current field, each weighted by 1/sigma^2. An affine fit that is
/// ill-conditioned (fewer than 6 supporting samples, or all on a line) keeps the previous field.
template <class Scalar>
ResidualField<Scalar> dominant_field(const FieldSamples<Scalar>& samples, ResidualCenter center,
                                     double window, int iterations, std::vector<Scalar>& scratch,
                                     FieldStart<Scalar>* start = nullptr) {
  using Vec2 = Eigen::Matrix<Scalar, 2, 1>;
  using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
  using Mat3 = Eigen::Matrix<Scalar, 3, 3>;
  ResidualField<Scalar> field;
  if (center == ResidualCenter::None) return field;
  field.offset = dominant_residual(samples, window, iterations, scratch, start);
  const std::size_t m = samples.size();
  if (center != ResidualCenter::Affine || m < 6) return field;

  // Origin at the mean prediction and a 100 px unit keep the normal equations well scaled.
  Scalar su = 0, sv = 0;
  for (std::size_t i = 0; i < m; ++i) {
    su += samples.u[i];
    sv += samples.v[i];
  }
  field.origin = Vec2(su, sv) / static_cast<Scalar>(m);
  const Scalar inv_unit = Scalar(0.01);
  const auto window2 = static_cast<Scalar>(window * window);
  for (int it = 0; it < std::max(iterations, 1); ++it) {
    // Normal equations of the weighted fit, accumulated as scalars (the symmetric 3 x 3 has six
    // distinct entries) so the loop stays in registers.
    Scalar a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0;
    Scalar bx0 = 0, bx1 = 0, bx2 = 0, by0 = 0, by1 = 0, by2 = 0;
    const Scalar ox = field.offset.x(), oy = field.offset.y();
    const Scalar g00 = field.gradient(0, 0) * Scalar(100), g01 = field.gradient(0, 1) * Scalar(100);
    const Scalar g10 = field.gradient(1, 0) * Scalar(100), g11 = field.gradient(1, 1) * Scalar(100);
    std::size_t support = 0;
    for (std::size_t i = 0; i < m; ++i) {
      const Scalar du = (samples.u[i] - field.origin.x()) * inv_unit;
      const Scalar dv = (samples.v[i] - field.origin.y()) * inv_unit;
      const Scalar ex = samples.rx[i] - (ox + g00 * du + g01 * dv);
      const Scalar ey = samples.ry[i] - (oy + g10 * du + g11 * dv);
      const Scalar w = samples.w[i];
      if ((ex * ex + ey * ey) * w > window2) continue;
      const Scalar wu = w * du, wv = w * dv;
      a00 += w;
      a01 += wu;
      a02 += wv;
      a11 += wu * du;
      a12 += wu * dv;
      a22 += wv * dv;
      bx0 += w * samples.rx[i];
      bx1 += wu * samples.rx[i];
      bx2 += wv * samples.rx[i];
      by0 += w * samples.ry[i];
      by1 += wu * samples.ry[i];
      by2 += wv * samples.ry[i];
      ++support;
    }
    Mat3 A;
    A << a00, a01, a02, a01, a11, a12, a02, a12, a22;
    const Vec3 bx(bx0, bx1, bx2), by(by0, by1, by2);
    if (support < 6) break;
    const Eigen::LDLT<Mat3> ldlt(A);
    // Reject a near-singular fit (predictions on a line): keep the previous field.
    if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > Scalar(1e-6))) break;
    const Vec3 cx = ldlt.solve(bx);
    const Vec3 cy = ldlt.solve(by);
    if (!cx.allFinite() || !cy.allFinite()) break;
    const Vec2 previous = field.offset;
    const Eigen::Matrix<Scalar, 2, 2> previous_gradient = field.gradient;
    field.offset = Vec2(cx(0), cy(0));
    field.gradient << cx(1) * inv_unit, cx(2) * inv_unit, cy(1) * inv_unit, cy(2) * inv_unit;
    // Converged when the field moves by less than 1e-3 px anywhere within 400 px of the origin.
    const Scalar change = (field.offset - previous).norm() +
                          Scalar(400) * (field.gradient - previous_gradient).norm();
    if (change < Scalar(1e-3)) break;
  }
  return field;
}

}  // namespace detail
}  // namespace hbos
