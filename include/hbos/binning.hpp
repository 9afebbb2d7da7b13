#pragma once
/// \file
/// How a feature is cut into bins: the binning method, the bin-count rule and the per-feature
/// specification (periodic features, one-sided tails).
///
/// Bin-count rules (n samples, range R = max - min):
///
/// - Fixed: `Binning::bins`.
/// - Sqrt: ceil(sqrt(n)) (Goldstein & Dengel 2012, the HBOS paper's default).
/// - Sturges: ceil(log2(n) + 1) (Sturges 1926).
/// - Scott: ceil(R / h), h = (24 sqrt(pi) / n)^(1/3) * std (Scott 1979).
/// - FreedmanDiaconis: ceil(R / h), h = 2 IQR n^(-1/3) (Freedman & Diaconis 1981).
/// - BirgeRozenblac: argmax over b = 1..floor(sqrt(n)) of
///   sum_k N_k ln(b N_k / n) - (b - 1 + ln(b)^2.5) (Birgé & Rozenblac 2006, eq. (2)).
///
/// Scott and Freedman–Diaconis fall back to Sturges when their width is zero (constant or
/// heavily tied data). Birgé–Rozenblac counts its penalty once per candidate b, as published
/// (PyOD subtracts it b times: that variant lives in hbos/pyod/model.hpp). Its search stops at
/// floor(sqrt(n)) and costs O(n) in total (detail::EdgeCounter).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)
#include <emmintrin.h>
#define HBOS_DETAIL_BINNING_SSE2 1
#endif

#include "hbos/detail/column_view.hpp"
#include "hbos/detail/scaling.hpp"
#include "hbos/error.hpp"

namespace hbos {

/// How bin edges are placed.
enum class BinningMethod {
  EqualWidth,     ///< k equal bins over [min, max] (static bins; Goldstein & Dengel)
  FixedWidth,     ///< bins of a given width with edges at origin + j * width (the paper's 0.01)
  EqualFrequency  ///< about n/k sorted values per bin, a run of equal values never split (dynamic
                  ///< bins)
};

/// How many bins (EqualWidth, EqualFrequency; ignored by FixedWidth).
enum class BinCountRule { Fixed, Sqrt, Sturges, Scott, FreedmanDiaconis, BirgeRozenblac };

/// Which side of a feature's distribution is anomalous.
///
/// `Upper` is the rule for residual magnitudes: a value at or below the modal bin contributes 0,
/// and above it the contribution never decreases with the value (a running maximum of the
/// two-sided contribution), so a match that fits *better* than typical is never penalised and a
/// secondary mode far out in the tail (a walking person) is not excused by its own density.
enum class Tail {
  Both,   ///< classic HBOS: any sparse bin is anomalous
  Upper,  ///< only large values are anomalous; score non-decreasing in the value
  Lower   ///< only small values are anomalous; score non-increasing in the value
};

/// Binning of one feature.
struct Binning {
  BinningMethod method = BinningMethod::EqualWidth;  ///< edge placement
  BinCountRule rule = BinCountRule::Fixed;           ///< bin count (EqualWidth, EqualFrequency)
  Eigen::Index bins = 10;                            ///< bin count for rule Fixed, >= 1
  double width = 0.01;  ///< [feature units] bin width for FixedWidth, > 0
  double origin = 0.0;  ///< [feature units] FixedWidth edges lie at origin + j * width
  /// Averaged shifted histograms (Scott 1985): the average of `shifts` histograms whose origins
  /// are offset by 1/shifts of a bin, computed on a grid `shifts` times finer with triangular
  /// weights. It removes the arbitrariness of the bin origin; 1 = the plain histogram.
  /// EqualWidth and FixedWidth only (EqualFrequency ignores it).
  Eigen::Index shifts = 1;
  /// Upper bound on any bin count (fine bins with shifts), in [1, kMaxBinsLimit].
  Eigen::Index max_bins = 65536;
};

/// The largest legal Binning::max_bins: 2^24 bins (about 0.7 GB of histogram per feature in
/// double), so that no parameter value asks for memory no machine has.
inline constexpr Eigen::Index kMaxBinsLimit = Eigen::Index{1} << 24;

/// Everything the model needs to know about one feature.
struct FeatureSpec {
  Binning binning{};       ///< how to bin this feature
  Tail tail = Tail::Both;  ///< which side is anomalous (non-periodic features only)
  bool periodic = false;   ///< an angle-like feature: values wrap modulo `period`
  double period_start = -3.14159265358979323846;  ///< [feature units] start of the period
  double period = 2.0 * 3.14159265358979323846;   ///< [feature units] length of the period, > 0
};

/// A periodic feature spec for angles in radians, [-pi, pi), with k equal bins on the circle.
[[nodiscard]] inline FeatureSpec angle_feature(Eigen::Index bins = 16) {
  FeatureSpec spec;
  spec.periodic = true;
  spec.binning.method = BinningMethod::EqualWidth;
  spec.binning.rule = BinCountRule::Fixed;
  spec.binning.bins = bins;
  return spec;
}

namespace detail {

/// std::allocator, except that a value-initialised element (what vector::resize appends) is left
/// uninitialised. For scratch buffers that are written before they are read: zeroing
/// Birgé–Rozenblac's buffer (then 2n doubles) cost a pass over 16 MB per column at n = 1e6.
template <class T>
struct UninitializedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <class U>
  UninitializedAllocator(const UninitializedAllocator<U>& /*other*/) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// A vector of doubles that resize() does not zero.
using ScratchDoubles = std::vector<double, UninitializedAllocator<double>>;

inline void validate(const FeatureSpec& spec, Eigen::Index feature) {
  const Binning& b = spec.binning;
  require(b.max_bins >= 1 && b.max_bins <= kMaxBinsLimit, "feature ", feature,
          ": max_bins must lie in [1, ", kMaxBinsLimit, "], got ", b.max_bins);
  require(b.shifts >= 1, "feature ", feature, ": shifts must be >= 1, got ", b.shifts);
  // Even one coarse bin holds `shifts` fine bins (EqualFrequency ignores shifts).
  require(b.method == BinningMethod::EqualFrequency || b.shifts <= b.max_bins, "feature ", feature,
          ": shifts ", b.shifts, " exceeds max_bins = ", b.max_bins);
  if (b.method == BinningMethod::FixedWidth) {
    require(std::isfinite(b.width) && b.width > 0.0, "feature ", feature,
            ": FixedWidth bin width must be finite and > 0, got ", b.width);
    require(std::isfinite(b.origin), "feature ", feature,
            ": FixedWidth origin must be finite, got ", b.origin);
  } else if (b.rule == BinCountRule::Fixed) {
    require(b.bins >= 1, "feature ", feature, ": bin count must be >= 1, got ", b.bins);
    require(b.bins <= b.max_bins, "feature ", feature, ": bin count ", b.bins, " exceeds max_bins ",
            b.max_bins);
  }
  if (spec.periodic) {
    require(std::isfinite(spec.period) && spec.period > 0.0, "feature ", feature,
            ": period must be finite and > 0, got ", spec.period);
    require(std::isfinite(spec.period_start), "feature ", feature,
            ": period_start must be finite, got ", spec.period_start);
    require(spec.tail == Tail::Both, "feature ", feature,
            ": a periodic feature has no upper or lower tail; use Tail::Both");
    require(b.method != BinningMethod::EqualFrequency, "feature ", feature,
            ": EqualFrequency binning is not defined on a circle; use EqualWidth or FixedWidth");
  }
}

/// The checks that depend on the model's scalar type: every parameter the bins are computed from
/// must be a normal Scalar (a float model cannot hold a period of 1e39 or a width of 1e-40).
template <class Scalar>
void validate_for_scalar(const FeatureSpec& spec, Eigen::Index feature) {
  using Limits = std::numeric_limits<Scalar>;
  const char* type = sizeof(Scalar) == sizeof(float) ? "float" : "double";
  const Binning& b = spec.binning;
  const auto max = static_cast<double>(Limits::max());
  const auto min = static_cast<double>(Limits::min());
  if (b.method == BinningMethod::FixedWidth) {
    require(b.width <= max, "feature ", feature, ": FixedWidth bin width ", b.width,
            " exceeds the largest ", type, " (", Limits::max(), ")");
    require(b.width / static_cast<double>(b.shifts) >= min, "feature ", feature,
            ": FixedWidth bin width ", b.width, " / ", b.shifts,
            " shifts is below the smallest normal ", type, " (", Limits::min(), ")");
  }
  if (spec.periodic) {
    require(spec.period <= max, "feature ", feature, ": period ", spec.period,
            " exceeds the largest ", type, " (", Limits::max(), ")");
    require(std::abs(spec.period_start) <= max, "feature ", feature, ": period_start ",
            spec.period_start, " is beyond the range of ", type, " (", Limits::max(), ")");
  }
}

[[nodiscard]] inline Eigen::Index clamp_bins(double k, Eigen::Index max_bins) {
  if (!(k >= 1.0)) return 1;  // also catches NaN
  if (k >= static_cast<double>(max_bins)) return max_bins;
  return static_cast<Eigen::Index>(k);
}

[[nodiscard]] inline Eigen::Index sturges_bins(Eigen::Index n) {
  return static_cast<Eigen::Index>(std::ceil(std::log2(static_cast<double>(n)) + 1.0));
}

/// Bins covering `range` at width `h`, or Sturges when the width degenerates to zero.
[[nodiscard]] inline Eigen::Index bins_from_width(double range, double h, Eigen::Index n,
                                                  Eigen::Index max_bins) {
  if (!(h > 0.0) || !(range > 0.0))
    return clamp_bins(static_cast<double>(sturges_bins(n)), max_bins);
  return clamp_bins(std::ceil(range / h), max_bins);
}

/// Exact counts of `u b < k` (u = (v - lo) * (1 / (hi - lo)) in double, as the direct count
/// computes it) for any candidate b and edge k, without a pass over the data per query.
///
/// The u are bucketed once into M ~ n/4 cells by a counting sort (O(n)). For an edge at u = k/b,
/// its position in cell units is p = k M / b. Unless p lies within 1e-4 of a cell boundary,
/// every value in a cell below p's cell has u b < k by a margin of at least b 1e-4 / M
/// (>= 3.8e-10 for M <= 2^18) and every value in a cell above it fails by as much, while the
/// rounding of u M, p and u b is below 1.2e-10 in cell units: only the ~4 values of p's own cell
/// are compared, with the very comparison `u b < k` of the direct count. Near a boundary (rare:
/// 2e-4 of the edges) the neighbouring cells are compared too. tests/unit/test_binning.cpp checks
/// every (b, k) against a direct count, on data placed exactly on and next to the edges.
class EdgeCounter {
 public:
  /// Buckets `n` values x[i * stride] of range [lo, hi] (hi > lo) into values[0, n); `values`
  /// (grown to at least n + the largest group of 256 cells, its old contents dropped when it
  /// grows) and `index` are reusable buffers (no allocation once grown).
  /// `scale` (a power of two, detail::rule_scale) is applied to every value first, so that
  /// ranges which overflow or underflow a double still give u in [0, 1]; 1 changes nothing.
  template <class Scalar, class Values>
  EdgeCounter(const Scalar* x, Eigen::Index n, Eigen::Index stride, Scalar lo, Scalar hi,
              Values& values, std::vector<std::uint32_t>& index, double scale = 1.0)
      : cells_(static_cast<std::size_t>(std::clamp<Eigen::Index>(n / 4, 64, 1 << 18))),
        dcells_(static_cast<double>(cells_)),
        index_(index) {
    const double base = static_cast<double>(lo) * scale;
    const double inv_range = 1.0 / (static_cast<double>(hi) * scale - base);
    const auto u_of = [&](Eigen::Index i) {
      return (static_cast<double>(x[i * stride]) * scale - base) * inv_range;
    };
    // Counting sort by cell, in two scatters: first into coarse groups of 256 cells, then each
    // group, now small enough for L1, into its cells (in place, through a copy of the group).
    // Scattered straight into ~n/4 cells, nearly every write would miss the cache (the write
    // cursors span the whole array). u is recomputed in the second pass rather than stored: two
    // flops are cheaper than another n doubles of memory traffic.
    const auto un = static_cast<std::size_t>(n);
    constexpr std::size_t group_shift = 8;
    const std::size_t groups = ((cells_ - 1) >> group_shift) + 1;
    index_.resize(cells_ + 1 + groups);
    std::uint32_t* cell_start = index_.data();
    std::uint32_t* group_cursor = cell_start + cells_ + 1;
    std::fill(cell_start, cell_start + cells_ + 1, 0U);
    for (Eigen::Index i = 0; i < n; ++i) ++cell_start[cell_of(u_of(i)) + 1];
    for (std::size_t c = 0; c < cells_; ++c) cell_start[c + 1] += cell_start[c];
    // cell_start[c] is where cell c begins: group g starts at cell_start[g * 256].
    const auto group_begin = [&](std::size_t g) {
      return cell_start[std::min(cells_, g << group_shift)];
    };
    std::size_t largest_group = 0;
    for (std::size_t g = 0; g < groups; ++g) {
      group_cursor[g] = group_begin(g);
      largest_group = std::max<std::size_t>(largest_group, group_begin(g + 1) - group_begin(g));
    }
    // values = [the bucketed values (n) | a copy of one group]. Grown without keeping the old
    // contents (nothing in it is needed yet): no copy, and no zeroing with ScratchDoubles.
    if (values.size() < un + largest_group) {
      values.clear();
      values.resize(un + largest_group);
    }
    double* bucketed = values.data();
    double* group_copy = bucketed + un;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double u = u_of(i);
      bucketed[group_cursor[cell_of(u) >> group_shift]++] = u;
    }
    // Each group into its cells, in place through a copy of the group (L1-sized for all but very
    // uneven data). cell_start[c] serves as cell c's cursor; afterwards it holds the start of
    // cell c + 1.
    for (std::size_t g = 0, begin = 0; g < groups; ++g) {
      const std::size_t end = group_cursor[g];  // the group's end, after the scatter above
      std::copy(bucketed + begin, bucketed + end, group_copy);
      for (std::size_t i = 0; i < end - begin; ++i)
        bucketed[cell_start[cell_of(group_copy[i])]++] = group_copy[i];
      begin = end;
    }
    for (std::size_t c = cells_; c > 0; --c) cell_start[c] = cell_start[c - 1];
    cell_start[0] = 0;
    by_cell_ = values.data();
  }

  /// Number of values with u b < k, for 0 < k < b.
  [[nodiscard]] std::uint32_t below(double b, double k) const {
    return below_at(b, k, position(b, k));
  }

  /// Calls visit(b, k, below(b, k)) for every b = 2..b_max and k = 1..b-1: for each b in
  /// increasing k, but overall chunk by chunk of cells (kChunkCells, about 32 KB of values, so
  /// L1-resident while its edges are counted). Asked for b by b, the ~b_max^2 / 2 edges jump
  /// across the whole array and nearly every one is a cache miss (most of the search time for
  /// n = 1e6); chunk by chunk the values are read in one sequential sweep. Each b keeps its next
  /// k and that edge's position: a b with no edge in the chunk costs one comparison.
  template <class Visit>
  void for_each_edge(Eigen::Index b_max, Visit&& visit) {
    const auto nb = static_cast<std::size_t>(std::max<Eigen::Index>(b_max, 1)) + 1;
    // index_ = [cell_start (M + 1) | per b: its next k (b_max + 1) | per b: the position of
    // that edge, a double in two slots (2 (b_max + 1))].
    index_.resize(cells_ + 1 + 3 * nb);
    std::uint32_t* next_k = index_.data() + cells_ + 1;
    std::uint32_t* next_p = next_k + nb;
    const auto load_p = [&](std::size_t b) {
      double p;
      std::memcpy(&p, next_p + 2 * b, sizeof p);
      return p;
    };
    const auto store_p = [&](std::size_t b, double p) {
      std::memcpy(next_p + 2 * b, &p, sizeof p);
    };
    for (std::size_t b = 2; b < nb; ++b) {
      next_k[b] = 1;
      store_p(b, position(static_cast<double>(b), 1.0));
    }
    constexpr double done = std::numeric_limits<double>::infinity();
    for (std::size_t begin = 0; begin < cells_; begin += kChunkCells) {
      // An edge lies in this chunk or an earlier one iff its cell min(M - 1, floor(p)) is below
      // `end`, i.e. iff p < end (p < M always, and end is a whole number).
      const double end = static_cast<double>(std::min(cells_, begin + kChunkCells));
      for (std::size_t b = 2; b < nb; ++b) {
        double p = load_p(b);
        if (!(p < end)) continue;
        const auto ub = static_cast<std::uint32_t>(b);
        const double db = static_cast<double>(b);
        std::uint32_t k = next_k[b];
        do {
          visit(ub, k, below_at(db, static_cast<double>(k), p));
          ++k;
          p = k < ub ? position(db, static_cast<double>(k)) : done;
        } while (p < end);
        next_k[b] = k;
        store_p(b, p);
      }
    }
  }

 private:
  static constexpr std::size_t kChunkCells = 1024;

  /// Where edge k/b lies, in cell units.
  [[nodiscard]] double position(double b, double k) const { return k * dcells_ / b; }

  /// below(b, k) for the edge at p = position(b, k).
  [[nodiscard]] std::uint32_t below_at(double b, double k, double p) const {
    // p > 0: truncation is floor (and, unlike std::floor, one instruction in SSE2).
    const auto cell = static_cast<std::int64_t>(p);
    const double frac = p - static_cast<double>(cell);
    const auto m = std::min(cells_ - 1, static_cast<std::size_t>(cell));
    const bool near_boundary = frac < 1e-4 || frac > 1.0 - 1e-4;
    const std::size_t first_cell = near_boundary && m > 0 ? m - 1 : m;
    const std::size_t end_cell = std::min(cells_, near_boundary ? m + 2 : m + 1);
    const std::uint32_t first = index_[first_cell];
    const std::uint32_t last = index_[end_cell];
    std::uint32_t count = first;
    std::uint32_t i = first;
#ifdef HBOS_DETAIL_BINNING_SSE2
    // Two values at a time: the same products and comparisons as the scalar loop (mulpd rounds
    // as mulsd does); each true lane adds 1 (its all-ones mask is -1).
    const __m128d vb = _mm_set1_pd(b);
    const __m128d vk = _mm_set1_pd(k);
    __m128i below_k = _mm_setzero_si128();
    for (; last - i >= 2; i += 2) {
      const __m128d lt = _mm_cmplt_pd(_mm_mul_pd(_mm_loadu_pd(by_cell_ + i), vb), vk);
      below_k = _mm_sub_epi64(below_k, _mm_castpd_si128(lt));
    }
    below_k = _mm_add_epi64(below_k, _mm_unpackhi_epi64(below_k, below_k));
    count += static_cast<std::uint32_t>(_mm_cvtsi128_si32(below_k));
#endif
    for (; i < last; ++i) count += by_cell_[i] * b < k ? 1U : 0U;
    return count;
  }
  /// Cells by truncation; through int64 because double -> uint64 has no single SSE2
  /// instruction (u * M lies in [0, M] here).
  [[nodiscard]] std::size_t cell_of(double u) const {
    return std::min(cells_ - 1, static_cast<std::size_t>(static_cast<std::int64_t>(u * dcells_)));
  }

  std::size_t cells_;
  double dcells_;
  // [cell_start (M + 1) | scratch]: the sort's group cursors, then for_each_edge's per-b state.
  std::vector<std::uint32_t>& index_;
  const double* by_cell_ = nullptr;
};

/// Birgé–Rozenblac's penalised log-likelihood maximiser over b = 1..floor(sqrt(n)).
///
/// Candidate b puts value v in bin floor(u b) with u = (v - lo) * (1 / (hi - lo)) (the last bin
/// closed). Counting every candidate directly costs O(n sqrt(n)) = 1e9 steps for n = 1e6; with
/// an EdgeCounter each of the ~n/2 interior edges of all candidates costs ~4 comparisons, so the
/// search is O(n) in total (plus one log per bin).
///
/// `values` and `index` are reusable buffers (no allocation once grown).
template <class Scalar, class Values>
[[nodiscard]] Eigen::Index birge_rozenblac_bins(const Scalar* x, Eigen::Index n,
                                                Eigen::Index stride, Scalar lo, Scalar hi,
                                                Eigen::Index max_bins, Values& values,
                                                std::vector<std::uint32_t>& index,
                                                double scale = 1.0) {
  if (!(hi > lo) || n < 4) return 1;
  const auto b_max = std::min<Eigen::Index>(
      max_bins,
      std::max<Eigen::Index>(1, static_cast<Eigen::Index>(std::sqrt(static_cast<double>(n)))));
  // Per b: the running sum of N_k ln N_k over its bins so far and the cumulative count at its
  // last edge; then a table of N ln N. They live in `values` after the n bucketed values (where
  // the sort kept its copy of a group).
  const auto nb = static_cast<std::size_t>(b_max) + 1;
  const auto un = static_cast<std::size_t>(n);
  // Grown before the counter fills it (the counter may grow it further, never shrink it).
  if (values.size() < un + 2 * nb + 4096) {
    values.clear();
    values.resize(un + 2 * nb + 4096);
  }
  EdgeCounter counter(x, n, stride, lo, hi, values, index, scale);
  double* sum_n_log_n = values.data() + un;
  double* cumulative = sum_n_log_n + nb;
  std::fill(sum_n_log_n, sum_n_log_n + 2 * nb, 0.0);
  // N ln N for the small counts most bins of the large candidates hold (n / b ~ sqrt(n)),
  // tabulated once: the ~n/2 bins of all candidates would otherwise cost a log each. Same values
  // as computing them in place (std::log of the same double), so the choice of b is unchanged.
  const std::size_t table_size = std::min<std::size_t>(un + 1, 4096);
  double* n_log_n = cumulative + nb;
  for (std::size_t c = 0; c < table_size; ++c) {
    const double dc = static_cast<double>(c);
    n_log_n[c] = c > 1 ? dc * std::log(dc) : 0.0;
  }
  auto add_bin = [&](std::size_t b, double at_edge) {
    const double count = at_edge - cumulative[b];
    const auto c = static_cast<std::size_t>(static_cast<std::int64_t>(count));
    sum_n_log_n[b] += c < table_size ? n_log_n[c] : count * std::log(count);
    cumulative[b] = at_edge;
  };
  counter.for_each_edge(b_max, [&](std::uint32_t b, std::uint32_t, std::uint32_t below) {
    add_bin(b, static_cast<double>(below));
  });
  const double dn = static_cast<double>(n);
  Eigen::Index best_b = 1;
  double best_l = -std::numeric_limits<double>::infinity();
  for (Eigen::Index b = 1; b <= b_max; ++b) {
    const auto ub = static_cast<std::size_t>(b);
    add_bin(ub, dn);  // the last bin, closed at hi
    // sum_k N_k ln(b N_k / n) = sum_k N_k ln N_k + n ln(b / n).
    const double db = static_cast<double>(b);
    const double penalty = db - 1.0 + std::pow(std::log(db), 2.5);
    const double l = sum_n_log_n[ub] + dn * std::log(db / dn) - penalty;
    if (l > best_l) {  // strict: the smallest b wins ties
      best_l = l;
      best_b = b;
    }
  }
  return best_b;
}

/// Where one feature's bins sit: what edge placement decides and counting and scoring read.
///
/// Uniform bins cut x at (x * scale - base) * inv_width. The scale is a power of two, 1 on every
/// ordinary column (then base == lo and the offset is plain x - lo); a column whose range
/// overflows Scalar (-1e308 to 1e308) or whose bins would be narrower than the smallest normal
/// Scalar (a subnormal range) is binned in that scaled form instead, with the same bins.
template <class Scalar>
struct EdgeLayout {
  std::vector<Scalar> edges;  ///< bins + 1 ascending edges; bin k is [edges[k], edges[k+1])
  Scalar lo = 0, hi = 0;      ///< the fitted range (the period for a periodic feature)
  Scalar inv_width = 0;       ///< uniform bins only (0 for a constant feature), of scaled values
  Scalar period = 0;          ///< periodic only
  Scalar scale = 1;           ///< uniform bins: power of two applied to values before binning
  Scalar base = 0;            ///< lo * scale
  /// Uniform bins: the fine bin width the edges were placed with (edges[j] = lo + j * fine, or
  /// (base + j * fine) / scale), which model files store instead of the edges; 0 otherwise.
  Scalar fine = 0;
};

/// The bin-count rules' reusable buffers (Birgé–Rozenblac's bucketed values and cells) and the
/// prefix sums of the linear-time averaged shifted histogram.
struct RuleScratch {
  ScratchDoubles values;
  std::vector<std::uint32_t> cells;
  std::vector<std::int64_t> sums;
};

/// The bin count `binning.rule` gives column `x` over [lo, hi].
template <class Scalar>
Eigen::Index rule_bins(const ColumnView<Scalar>& x, const Binning& binning, Scalar lo, Scalar hi,
                       std::vector<Scalar>& scratch, RuleScratch& rule_scratch) {
  const Eigen::Index n = x.size;
  // Values are read times s (1 on ordinary columns, see rule_scale): bin counts are invariant
  // under it, and extreme columns (1e308, subnormals) then neither overflow nor underflow.
  const double s = rule_scale(static_cast<double>(lo), static_cast<double>(hi));
  const double range = static_cast<double>(hi) * s - static_cast<double>(lo) * s;
  const double dn = static_cast<double>(n);
  switch (binning.rule) {
    case BinCountRule::Fixed:
      return binning.bins;
    case BinCountRule::Sqrt:
      return clamp_bins(std::ceil(std::sqrt(dn)), binning.max_bins);
    case BinCountRule::Sturges:
      return clamp_bins(static_cast<double>(sturges_bins(n)), binning.max_bins);
    case BinCountRule::Scott: {
      double mean = 0.0;
      for (Eigen::Index i = 0; i < n; ++i) mean += static_cast<double>(x[i]) * s;
      mean /= dn;
      double ss = 0.0;
      for (Eigen::Index i = 0; i < n; ++i) {
        const double d = static_cast<double>(x[i]) * s - mean;
        ss += d * d;
      }
      const double h =
          std::cbrt(24.0 * std::sqrt(3.14159265358979323846) / dn) * std::sqrt(ss / dn);
      return bins_from_width(range, h, n, binning.max_bins);
    }
    case BinCountRule::FreedmanDiaconis: {
      // numpy's linear-interpolation quartiles by selection (O(n)) on a copy.
      if (x.data != scratch.data()) {
        scratch.resize(static_cast<std::size_t>(n));
        for (Eigen::Index i = 0; i < n; ++i) scratch[static_cast<std::size_t>(i)] = x[i];
      }
      auto quantile = [&](double q) {
        const double pos = q * (dn - 1.0);
        const auto i = static_cast<std::ptrdiff_t>(std::floor(pos));
        const double g = pos - static_cast<double>(i);
        std::nth_element(scratch.begin(), scratch.begin() + i, scratch.begin() + n);
        const double a = static_cast<double>(scratch[static_cast<std::size_t>(i)]) * s;
        const double b = i + 1 < n ? static_cast<double>(*std::min_element(scratch.begin() + i + 1,
                                                                           scratch.begin() + n)) *
                                         s
                                   : a;
        return a + (b - a) * g;
      };
      const double q1 = quantile(0.25);
      const double iqr = quantile(0.75) - q1;
      return bins_from_width(range, 2.0 * iqr / std::cbrt(dn), n, binning.max_bins);
    }
    case BinCountRule::BirgeRozenblac:
      return birge_rozenblac_bins(x.data, n, x.stride, lo, hi, binning.max_bins,
                                  rule_scratch.values, rule_scratch.cells, s);
  }
  return binning.bins;
}

/// The k + 1 edges of k uniform bins of width `fine` from lo (in scaled units when scale != 1),
/// the last one hi: how place_uniform_edges places them, and how a model file that stores only
/// `fine` rebuilds them, bit for bit.
template <class Scalar>
void fill_uniform_edges(Scalar lo, Scalar hi, Scalar scale, Scalar base, Scalar fine,
                        Eigen::Index k, std::vector<Scalar>& edges) {
  edges.resize(static_cast<std::size_t>(k + 1));
  if (scale == Scalar(1)) {
    for (Eigen::Index j = 0; j < k; ++j)
      edges[static_cast<std::size_t>(j)] = lo + static_cast<Scalar>(j) * fine;
  } else {
    for (Eigen::Index j = 0; j < k; ++j)
      edges[static_cast<std::size_t>(j)] = (base + static_cast<Scalar>(j) * fine) / scale;
  }
  edges.back() = hi;
}

/// FixedWidth bins over the column range [lo, hi]: sets layout.lo, layout.hi and returns the
/// coarse bin count. Edges sit at origin + j * width while the offsets (v - origin) / width stay
/// below 2^53 (beyond, floor(q) + 1 == floor(q) and no edge index exists): then the bins keep
/// their width but start at the column minimum. Either way lo <= every value <= hi.
/// \throws InvalidArgument when the bins exceed max_bins.
template <class Scalar>
Eigen::Index place_fixed_width(const Binning& binning, Eigen::Index shifts, Scalar lo, Scalar hi,
                               Eigen::Index feature, EdgeLayout<Scalar>& layout) {
  const double w = binning.width;
  const double o = binning.origin;
  const auto dlo = static_cast<double>(lo);
  const auto dhi = static_cast<double>(hi);
  const double q_lo = (dlo - o) / w;
  const double q_hi = (dhi - o) / w;
  const double first = std::floor(q_lo);
  const double last = std::floor(q_hi) + 1.0;
  double lo_edge = o + first * w;
  double hi_edge = o + last * w;
  double needed = last - first;
  constexpr double exact = 0x1p53;
  const bool anchored = std::abs(q_lo) < exact && std::abs(q_hi) < exact &&
                        std::isfinite(lo_edge) && std::isfinite(hi_edge);
  if (!anchored) {
    lo_edge = dlo;
    needed = std::floor(span_over(dlo, dhi, w)) + 1.0;
    hi_edge = dlo + needed * w;
  }
  require(needed <= static_cast<double>(binning.max_bins) / static_cast<double>(shifts), "feature ",
          feature, ": fixed bin width ", binning.width, " over the range [", lo, ", ", hi,
          "] needs ", needed, " bins, more than max_bins = ", binning.max_bins);
  // Rounding of o + j * w must never leave a value outside its own layout.
  layout.lo = saturate_cast<Scalar>(std::min(lo_edge, dlo));
  layout.hi = saturate_cast<Scalar>(std::max(hi_edge, dhi));
  return static_cast<Eigen::Index>(needed);
}

/// Uniform bins (equal or fixed width, periodic or not) for `x`, `shifts` fine bins per coarse
/// bin, into `layout` (see EdgeLayout for the scaled form of extreme columns).
/// \throws InvalidArgument when the bins exceed `max_bins`, or a period is too short for its
/// bins to be normal Scalars.
template <class Scalar>
void place_uniform_edges(const ColumnView<Scalar>& x, const FeatureSpec& spec, Eigen::Index shifts,
                         std::vector<Scalar>& scratch, RuleScratch& rule_scratch,
                         Eigen::Index feature, EdgeLayout<Scalar>& layout) {
  using Limits = std::numeric_limits<Scalar>;
  const Binning& binning = spec.binning;
  const bool fixed = binning.method == BinningMethod::FixedWidth;
  Eigen::Index k = 1;
  Scalar width = 0;
  layout.scale = 1;
  if (spec.periodic) {
    layout.lo = static_cast<Scalar>(spec.period_start);  // validate_for_scalar: representable
    layout.period = static_cast<Scalar>(spec.period);
    layout.hi = saturate_cast<Scalar>(spec.period_start + spec.period);
    if (fixed) {
      // The period must hold a whole number of bins: the width is rounded to the nearest divisor.
      k = clamp_bins(std::round(spec.period / binning.width), binning.max_bins);
    } else {
      k = rule_bins(x, binning, Scalar(0), layout.period, scratch, rule_scratch);
    }
    width = layout.period / static_cast<Scalar>(k);
  } else {
    const auto [lo, hi] = finite_min_max(x, feature);
    if (fixed) {
      k = place_fixed_width(binning, shifts, lo, hi, feature, layout);
      width = static_cast<Scalar>(binning.width);
    } else {
      layout.lo = lo;
      layout.hi = hi;
      if (layout.hi > layout.lo) {
        k = rule_bins(x, binning, layout.lo, layout.hi, scratch, rule_scratch);
        width = (layout.hi - layout.lo) / static_cast<Scalar>(k);
      }
    }
  }
  // Averaged shifted histograms count on a grid m times finer than the coarse bins (not for a
  // constant column: its one bin has no width to divide).
  const bool spread = fixed || spec.periodic || layout.hi > layout.lo;
  const Eigen::Index m = spread && shifts > 1 ? shifts : 1;
  require(k <= binning.max_bins / m, "feature ", feature, ": ", k, " bins x ", m,
          " shifts exceed max_bins = ", binning.max_bins);
  Scalar fine = m > 1 ? width / static_cast<Scalar>(m) : width;
  if (spec.periodic) {
    require(fine >= Limits::min(), "feature ", feature, ": period ", spec.period, " cut into ",
            k * m, " bins gives bins of width ", fine, ", below the smallest normal Scalar (",
            Limits::min(), "); use a longer period or fewer bins");
  } else if (spread && (!std::isfinite(layout.hi - layout.lo) || !(fine >= Limits::min()))) {
    // A range that overflows Scalar, or bins narrower than the smallest normal Scalar (1 / width
    // would be infinite): bin x * s instead, s a power of two that puts the values near 1.
    layout.scale = unit_scale(layout.lo, layout.hi);
    const Scalar s = layout.scale;
    width = fixed ? static_cast<Scalar>(binning.width) * s
                  : (layout.hi * s - layout.lo * s) / static_cast<Scalar>(k);
    fine = m > 1 ? width / static_cast<Scalar>(m) : width;
    require(fine >= Limits::min() && std::isfinite(fine), "feature ", feature,
            ": cannot bin the range [", layout.lo, ", ", layout.hi, "] into ", k * m, " bins");
  }
  k *= m;
  layout.base = layout.lo * layout.scale;
  layout.inv_width = fine > Scalar(0) ? Scalar(1) / fine : Scalar(0);
  layout.fine = fine;
  fill_uniform_edges(layout.lo, layout.hi, layout.scale, layout.base, fine, k, layout.edges);
}

/// The point midway between a < b, without the overflow of b - a (a = -1e308, b = 1e308).
template <class Scalar>
[[nodiscard]] Scalar midpoint(Scalar a, Scalar b) {
  const Scalar d = b - a;
  if (std::isfinite(d)) return a + d / Scalar(2);
  return a / Scalar(2) + b / Scalar(2);
}

template <class Scalar>
void place_equal_frequency_edges(const Scalar* sorted, Eigen::Index n, Eigen::Index k,
                                 EdgeLayout<Scalar>& layout) {
  // Goldstein & Dengel's dynamic bins: about n/k sorted values per bin; a boundary never splits
  // a run of equal values, so ties may merge bins. Edges sit midway between the last value of a
  // bin and the first of the next. Between adjacent doubles the midpoint rounds onto one of
  // them: an edge that would not lie strictly inside (previous edge, hi) is dropped, so every
  // bin has positive width.
  layout.lo = sorted[0];
  layout.hi = sorted[n - 1];
  layout.scale = 1;
  layout.base = layout.lo;
  layout.fine = 0;
  layout.edges.clear();
  layout.edges.push_back(layout.lo);
  Eigen::Index previous = 0;
  for (Eigen::Index b = 1; b < k; ++b) {
    auto p = static_cast<Eigen::Index>(
        std::llround(static_cast<double>(b) * static_cast<double>(n) / static_cast<double>(k)));
    if (p <= previous) continue;
    while (p < n && sorted[p] == sorted[p - 1]) ++p;
    if (p >= n) break;
    const Scalar edge = midpoint(sorted[p - 1], sorted[p]);
    if (edge > layout.edges.back() && edge < layout.hi) layout.edges.push_back(edge);
    previous = p;
  }
  layout.edges.push_back(layout.hi);
}

}  // namespace detail
}  // namespace hbos
