#pragma once
/// \file
/// How a feature is cut into bins: the binning method, the bin-count rule and the per-feature
/// specification (periodic features, one-sided tails).
///
/// Bin-count rules (n samples, range R = max - min):
///
/// | rule              | bins k                                            | reference |
/// |-------------------|---------------------------------------------------|----------------------------|
/// | Fixed             | `Binning::bins`                                   | | | Sqrt |
/// ceil(sqrt(n))                                     | Goldstein & Dengel 2012 (HBOS) | | Sturges
/// | ceil(log2(n) + 1)                                 | Sturges 1926               | | Scott |
/// ceil(R / h), h = (24 sqrt(pi) / n)^(1/3) * std    | Scott 1979                 | |
/// FreedmanDiaconis  | ceil(R / h), h = 2 IQR n^(-1/3)                   | Freedman & Diaconis 1981
/// | | BirgeRozenblac    | argmax_b sum_k N_k ln(b N_k / n) - (b - 1 + ln(b)^2.5), b
/// = 1..floor(sqrt(n)) | Birgé & Rozenblac 2006, eq. (2) |
///
/// Scott and Freedman–Diaconis fall back to Sturges when their width is zero (constant or
/// heavily tied data). Birgé–Rozenblac counts its penalty once per candidate b, as published
/// (PyOD subtracts it b times: that variant lives in pyod.hpp). Its search stops at floor(sqrt(n))
/// so that, with one sort and a binary search per edge, it costs O(n log n) in total.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

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
  Eigen::Index max_bins = 65536;  ///< upper bound on any bin count (fine bins with shifts), >= 1
};

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

inline void validate(const FeatureSpec& spec, Eigen::Index feature) {
  const Binning& b = spec.binning;
  require(b.max_bins >= 1, "feature ", feature, ": max_bins must be >= 1, got ", b.max_bins);
  require(b.shifts >= 1, "feature ", feature, ": shifts must be >= 1, got ", b.shifts);
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

/// Birgé–Rozenblac's penalised log-likelihood maximiser over b = 1..floor(sqrt(n)).
///
/// Candidate b puts value v in bin floor(u b) with u = (v - lo) * (1 / (hi - lo)) (the last bin
/// closed). Counting every candidate directly costs O(n sqrt(n)) = 1e9 steps for n = 1e6.
/// Instead the u are bucketed once into M ~ n/16 cells by a counting sort (O(n)). For an interior
/// edge k/b, every cell more than one below the edge's cell lies wholly below it (u b < k - b/M)
/// and every cell more than one above lies wholly above: margins far larger than any rounding.
/// Only the ~48 values of the three cells around the edge are compared, with the very
/// comparison `u b < k` of the direct count, so the counts are exactly the direct method's
/// (tests/unit/test_binning.cpp checks against a brute-force count). Total O(n + b_max^2 n / M)
/// = O(n) for M ~ n / 16 and b_max = sqrt(n).
///
/// `work` and `cell_start` are reusable buffers (no allocation once grown).
template <class Scalar>
[[nodiscard]] Eigen::Index birge_rozenblac_bins(const Scalar* x, Eigen::Index n,
                                                Eigen::Index stride, Scalar lo, Scalar hi,
                                                Eigen::Index max_bins, std::vector<double>& work,
                                                std::vector<std::uint32_t>& cell_start) {
  if (!(hi > lo) || n < 4) return 1;
  const double inv_range = 1.0 / (static_cast<double>(hi) - static_cast<double>(lo));
  const auto un = static_cast<std::size_t>(n);
  const auto cells = static_cast<std::size_t>(std::clamp<Eigen::Index>(n / 16, 64, 1 << 16));
  const double dcells = static_cast<double>(cells);
  auto cell_of = [&](double u) {
    return std::min(cells - 1, static_cast<std::size_t>(u * dcells));
  };

  // u for every value, then a counting sort by cell into the second half of `work`.
  work.resize(2 * un);
  double* u = work.data();
  double* by_cell = work.data() + un;
  cell_start.assign(cells + 1, 0);
  for (std::size_t i = 0; i < un; ++i) {
    u[i] =
        (static_cast<double>(x[static_cast<Eigen::Index>(i) * stride]) - static_cast<double>(lo)) *
        inv_range;
    ++cell_start[cell_of(u[i]) + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) cell_start[c + 1] += cell_start[c];
  // cell_start[c] serves as cell c's cursor; afterwards it holds the start of cell c + 1.
  for (std::size_t i = 0; i < un; ++i) by_cell[cell_start[cell_of(u[i])]++] = u[i];
  for (std::size_t c = cells; c > 0; --c) cell_start[c] = cell_start[c - 1];
  cell_start[0] = 0;

  // Number of values with u * b < k, k = 1..b-1.
  // The edge's cell needs no exactness (the neighbours are compared too): cells_per_unit = M/b.
  auto below = [&](double db, double cells_per_unit, double k) {
    const auto m = std::min(cells - 1, static_cast<std::size_t>(k * cells_per_unit));
    const std::uint32_t first = cell_start[m > 0 ? m - 1 : 0];
    const std::uint32_t last = cell_start[std::min(cells, m + 2)];
    std::uint32_t count = first;
    for (std::uint32_t i = first; i < last; ++i) count += by_cell[i] * db < k ? 1U : 0U;
    return static_cast<double>(count);
  };

  const auto b_max = std::min<Eigen::Index>(
      max_bins,
      std::max<Eigen::Index>(1, static_cast<Eigen::Index>(std::sqrt(static_cast<double>(n)))));
  const double dn = static_cast<double>(n);
  Eigen::Index best_b = 1;
  double best_l = -std::numeric_limits<double>::infinity();
  for (Eigen::Index b = 1; b <= b_max; ++b) {
    const double db = static_cast<double>(b);
    const double cells_per_unit = dcells / db;
    // sum_k N_k ln(b N_k / n) = sum_k N_k ln N_k + n ln(b / n).
    double sum_n_log_n = 0.0;
    double previous = 0.0;
    for (Eigen::Index k = 1; k <= b; ++k) {
      const double cumulative = k < b ? below(db, cells_per_unit, static_cast<double>(k)) : dn;
      const double count = cumulative - previous;
      if (count > 1.0) sum_n_log_n += count * std::log(count);
      previous = cumulative;
    }
    const double penalty = db - 1.0 + std::pow(std::log(db), 2.5);
    const double l = sum_n_log_n + dn * std::log(db / dn) - penalty;
    if (l > best_l) {  // strict: the smallest b wins ties
      best_l = l;
      best_b = b;
    }
  }
  return best_b;
}

}  // namespace detail
}  // namespace hbos
