#pragma once
/// \file
/// Spatial coherence of residuals: for each match, the mean residual of its neighbours in the
/// image and in depth, and the log-likelihood ratio that the match moves with them rather than
/// with the background (strategies.hpp, CoherenceEvidence, states the maths).
///
/// Neighbourhoods are cells of a grid over (u, v, log depth); a match's neighbours are the
/// support matches in the 3 x 3 (x 3 with depth) cells around its own. Cell sums are box-filtered
/// once per frame (three separable passes over the grid), so a frame costs O(n + cells), not
/// O(n k).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "hbos/screening/pixel_grid.hpp"

namespace hbos::detail {

/// The most cells a coherence grid has (so a workspace can reserve them): image cells grow and
/// depth layers merge beyond it.
inline constexpr std::size_t kMaxCoherenceCells = 16384;

/// Reusable buffers and the per-match inputs of coherence_evidence, column-wise.
template <class Scalar>
struct CoherenceWork {
  std::vector<Scalar> dx, dy;          ///< centred, whitened residual [px/sigma]
  std::vector<std::uint8_t> support;   ///< 1 = contributes to its neighbours' consensus
  std::vector<std::uint32_t> cell;     ///< the match's cell
  std::vector<Scalar> sx, sy, count;   ///< per cell
  std::vector<Scalar> tx, ty, tcount;  ///< per cell: the box-filtered sums, where evaluated
  /// per match: its depth layer; its residual clamped to the gate (support matches); its
  /// neighbours' sums (its own contribution taken out)
  std::vector<Scalar> layer, kx, ky, nsx, nsy, ncount;
  /// per evaluated match of a subset call: its residual and its evidence, compacted
  std::vector<Scalar> sub_dx, sub_dy, sub_llr;
  /// The grid of the last call (its size and `cell`), reused by the next call while `grid_valid`
  /// and its n, cell_px and depth_ratio are the same: the caller clears it whenever the pixels
  /// or depths may have changed. (The screen clears it per frame: its evidence rounds share the
  /// frame's pixels and depths, and the logarithm and divisions per match that place them were
  /// taken once per round.)
  bool grid_valid = false;
  std::size_t grid_n = 0, nx = 1, ny = 1, nl = 1;
  double grid_cell_px = 0.0, grid_depth_ratio = 0.0;
};

/// The cells of coherence_evidence (see there) into work.cell, the grid's size into work.nx,
/// ny, nl; marks the grid valid for these inputs.
template <class Scalar>
void coherence_grid(const Scalar* u, const Scalar* v, const Scalar* depth, std::size_t n,
                    double cell_px, double depth_ratio, CoherenceWork<Scalar>& work) {
  Scalar u0 = u[0], u1 = u[0], v0 = v[0], v1 = v[0];
  bool all_depth = true;
  Scalar l0 = std::numeric_limits<Scalar>::infinity(), l1 = -l0;
  const Scalar inv_log_ratio = Scalar(1) / static_cast<Scalar>(std::log(depth_ratio));
  work.layer.resize(n);  // a logarithm per match, taken once
  for (std::size_t i = 0; i < n; ++i) {
    u0 = std::min(u0, u[i]);
    u1 = std::max(u1, u[i]);
    v0 = std::min(v0, v[i]);
    v1 = std::max(v1, v[i]);
    if (!(depth[i] > Scalar(0)) || !std::isfinite(depth[i])) {
      all_depth = false;
    } else {
      const Scalar layer = std::floor(std::log(depth[i]) * inv_log_ratio);
      work.layer[i] = layer;
      l0 = std::min(l0, layer);
      l1 = std::max(l1, layer);
    }
  }
  // At most 128 x 128 cells (kMaxCoherenceCells; a coarser cell for a larger image) and 64 depth
  // layers (far depths share the last layer).
  const PixelGrid grid(static_cast<double>(u0), static_cast<double>(u1), static_cast<double>(v0),
                       static_cast<double>(v1), cell_px, 128.0);
  const std::size_t nx = grid.nx(), ny = grid.ny();
  const std::size_t layers = all_depth ? static_cast<std::size_t>(l1 - l0) + 1 : 1;
  const std::size_t max_layers = std::max<std::size_t>(1, kMaxCoherenceCells / (nx * ny));
  const std::size_t merge = (layers + max_layers - 1) / max_layers;  // layers per grid layer
  const std::size_t nl = (layers + merge - 1) / merge;
  work.cell.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t in_plane = grid.cell(static_cast<double>(u[i]), static_cast<double>(v[i]));
    std::size_t cl = 0;
    if (nl > 1) {
      const Scalar layer = work.layer[i] - l0;
      cl = std::min(static_cast<std::size_t>(layer) / merge, nl - 1);
    }
    work.cell[i] = static_cast<std::uint32_t>(cl * nx * ny + in_plane);
  }
  work.nx = nx;
  work.ny = ny;
  work.nl = nl;
  work.grid_n = n;
  work.grid_cell_px = cell_px;
  work.grid_depth_ratio = depth_ratio;
  work.grid_valid = true;
}

/// The statistic of coherence_evidence over m matches, column-wise: from the neighbours' sums
/// (nsx, nsy: overwritten) and counts and each match's own residual (dx, dy) into `out`. Eigen
/// arrays divide and take square roots two values at a time, where one match at a time waited
/// on each result in turn; every value sees the same operations in the same order whichever
/// matches share its column, so its bits do not depend on them.
template <class Scalar>
void coherence_statistic(Scalar* nsx, Scalar* nsy, const Scalar* ncount, const Scalar* dx_in,
                         const Scalar* dy_in, std::size_t m, Scalar scale, double z0, Scalar* llr) {
  using Array = Eigen::Array<Scalar, Eigen::Dynamic, 1>;
  const auto size = static_cast<Eigen::Index>(m);
  Eigen::Map<Array> cx(nsx, size), cy(nsy, size);
  const Eigen::Map<const Array> cnt(ncount, size);
  const Eigen::Map<const Array> dx(dx_in, size), dy(dy_in, size);
  Eigen::Map<Array> out(llr, size);
  // Eigen's float square root is approximate (see screen.hpp); double's is the exact sqrtpd.
  const auto sqrt = [](const auto& a) {
    if constexpr (std::is_same_v<Scalar, double>) {
      return a.sqrt();
    } else {
      return a.unaryExpr([](Scalar x) { return std::sqrt(x); });
    }
  };
  cx /= cnt;  // the neighbours' mean residual c_i (NaN where cnt < 2: masked below)
  cy /= cnt;
  const Scalar inv_2s2 = Scalar(1) / (Scalar(2) * scale * scale);
  const auto zz = static_cast<Scalar>(z0);
  // z_i = |c_i| sqrt(cnt) / s, then the shrink 1 - z0 / z_i where z_i > z0 (kept in `out`).
  out = sqrt(cx * cx + cy * cy) * sqrt(cnt) / scale;
  out = (out > zz).select(Scalar(1) - zz / out, Scalar(0));
  cx *= out;
  cy *= out;
  out = (cnt < Scalar(2))
            .select(Scalar(0), (Scalar(2) * (dx * cx + dy * cy) - (cx * cx + cy * cy)) * inv_2s2);
}

/// Fills `llr` (size n) with the coherence evidence of every match. `u`, `v` are the predicted
/// pixels, `depth` their depths (NaN = unknown; depth is used only when every match has one),
/// `work.dx/dy/support` must be filled; `gate` clamps each neighbour's contribution [px/sigma];
/// `scale` is the noise scale s (> 0). The cells are those of `work`'s grid while it is valid
/// (see CoherenceWork::grid_valid).
///
/// With `subset` (indices into the n matches; empty: none), only those matches' evidence is
/// evaluated and written to llr; the other entries of llr are left as they were. Every match
/// still supports its neighbours as `work.support` says, and an evaluated match goes through the
/// same operations in the same order as in a call over all n (the same bits: a unit test checks
/// them in the project's build).
template <class Scalar>
void coherence_evidence(const Scalar* u, const Scalar* v, const Scalar* depth, std::size_t n,
                        Scalar gate, Scalar scale, double cell_px, double depth_ratio, double z0,
                        CoherenceWork<Scalar>& work, Scalar* llr,
                        const std::vector<std::uint32_t>* subset = nullptr) {
  if (n == 0) return;
  if (!work.grid_valid || work.grid_n != n || work.grid_cell_px != cell_px ||
      work.grid_depth_ratio != depth_ratio) {
    coherence_grid(u, v, depth, n, cell_px, depth_ratio, work);
  }
  const std::size_t nx = work.nx, ny = work.ny, nl = work.nl;
  const std::size_t cells = nx * ny * nl;
  for (auto* a : {&work.sx, &work.sy, &work.count}) a->assign(cells, Scalar(0));
  work.kx.resize(n);
  work.ky.resize(n);
  // Below gate^2 less a margin of a few roundings, m = sqrt(|d|^2) cannot round above the gate:
  // k is 1 there without the square root (support matches lie within the gate, so that is
  // nearly every one); elsewhere m and k are taken as before. The margin holds only while gate^2
  // is a normal number (relative rounding); otherwise every match takes the square root (-1).
  const Scalar gate2 = gate * gate;
  const Scalar within2 =
      std::isfinite(gate2) && gate2 >= std::numeric_limits<Scalar>::min()
          ? gate2 * (Scalar(1) - Scalar(8) * std::numeric_limits<Scalar>::epsilon())
          : Scalar(-1);
  for (std::size_t i = 0; i < n; ++i) {
    if (!work.support[i]) continue;
    const Scalar m2 = work.dx[i] * work.dx[i] + work.dy[i] * work.dy[i];
    Scalar k = Scalar(1);
    if (!(m2 <= within2)) {
      const Scalar m = std::sqrt(m2);
      k = m > gate ? gate / m : Scalar(1);
    }
    const std::uint32_t c = work.cell[i];
    work.kx[i] = k * work.dx[i];
    work.ky[i] = k * work.dy[i];
    work.sx[c] += work.kx[i];
    work.sy[c] += work.ky[i];
    work.count[c] += Scalar(1);
  }
  // The 3-box sums along x, then y, then (when used) the depth layers, evaluated at the occupied
  // cells only: a separable filter over every cell cost more than the rest of the evidence when
  // the depth layers make the grid large and sparse. Each sum adds in the order the separable
  // passes would (centre, before, after), so the sums are theirs bit for bit. A cell's column,
  // row and layer are taken once (an integer division per neighbour and array, 48 a cell, was
  // most of the evidence's time), and the three arrays are summed together.
  const std::size_t plane = nx * ny;
  struct Sums {
    Scalar x, y, count;
    Sums& operator+=(const Sums& o) {
      x += o.x;
      y += o.y;
      count += o.count;
      return *this;
    }
  };
  const auto at = [&](std::size_t c) { return Sums{work.sx[c], work.sy[c], work.count[c]}; };
  const auto box = [&](std::size_t c) {
    const std::size_t cx = c % nx, cy = (c / nx) % ny, cl = c / plane;
    const auto box_x = [&](std::size_t k) {
      Sums sum = at(k);
      if (cx > 0) sum += at(k - 1);
      if (cx + 1 < nx) sum += at(k + 1);
      return sum;
    };
    const auto box_xy = [&](std::size_t k) {
      Sums sum = box_x(k);
      if (cy > 0) sum += box_x(k - nx);
      if (cy + 1 < ny) sum += box_x(k + nx);
      return sum;
    };
    Sums sum = box_xy(c);
    if (nl == 1) return sum;
    if (cl > 0) sum += box_xy(c - plane);
    if (cl + 1 < nl) sum += box_xy(c + plane);
    return sum;
  };
  // tx, ty, tcount memoise the sums per cell (tcount < 0: not yet evaluated).
  work.tx.resize(cells);
  work.ty.resize(cells);
  work.tcount.assign(cells, Scalar(-1));

  // The neighbours' sums of every evaluated match (a gather: scalar), then the statistic over
  // whole columns. `index_of(j)` is the j-th evaluated match; one loop per kind of call, so each
  // is compiled with its body in place.
  const auto gather = [&](std::size_t count, const auto& index_of) {
    for (auto* a : {&work.nsx, &work.nsy, &work.ncount}) a->resize(count);
    for (std::size_t j = 0; j < count; ++j) {
      const std::size_t i = index_of(j);
      const std::uint32_t c = work.cell[i];
      if (work.tcount[c] < Scalar(0)) {
        const Sums sum = box(c);
        work.tx[c] = sum.x;
        work.ty[c] = sum.y;
        work.tcount[c] = sum.count;
      }
      Scalar sx = work.tx[c], sy = work.ty[c], cnt = work.tcount[c];
      if (work.support[i]) {  // a match is not its own neighbour
        sx -= work.kx[i];
        sy -= work.ky[i];
        cnt -= Scalar(1);
      }
      work.nsx[j] = sx;
      work.nsy[j] = sy;
      work.ncount[j] = cnt;
    }
  };
  if (subset == nullptr) {
    gather(n, [](std::size_t j) { return j; });
    coherence_statistic(work.nsx.data(), work.nsy.data(), work.ncount.data(), work.dx.data(),
                        work.dy.data(), n, scale, z0, llr);
    return;
  }
  // Compacted: the evaluated matches' sums and residuals side by side, their evidence scattered
  // back to their places.
  const std::vector<std::uint32_t>& evaluated = *subset;
  const std::size_t m = evaluated.size();
  gather(m, [&](std::size_t j) { return static_cast<std::size_t>(evaluated[j]); });
  for (auto* a : {&work.sub_dx, &work.sub_dy, &work.sub_llr}) a->resize(m);
  for (std::size_t j = 0; j < m; ++j) {
    work.sub_dx[j] = work.dx[evaluated[j]];
    work.sub_dy[j] = work.dy[evaluated[j]];
  }
  coherence_statistic(work.nsx.data(), work.nsy.data(), work.ncount.data(), work.sub_dx.data(),
                      work.sub_dy.data(), m, scale, z0, work.sub_llr.data());
  for (std::size_t j = 0; j < m; ++j) llr[evaluated[j]] = work.sub_llr[j];
}

}  // namespace hbos::detail
