#pragma once
/// \file
/// numpy's arithmetic where PyOD's HBOS depends on it, reproduced bit for bit: the bin edges of
/// `numpy.histogram` (which come from `numpy.linspace`), the bin a value is counted in and the
/// bin `numpy.digitize(right=True)` finds for it, numpy's pairwise summation and percentile. Plus
/// the bucketed column that makes PyOD's `n_bins="auto"` search O(n) expected, O(n log n) worst.
///
/// Internal to hbos/pyod.hpp; the semantics are written down in docs/pyod_compat.md and in
/// tests/data/hbos_pyod/README.md.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "hbos/detail/numpy.hpp"  // detail::mul_rounded
#include "hbos/error.hpp"

namespace hbos::detail {

/// numpy's `_get_outer_edges`: the histogram range of a column, widened by 0.5 on each side
/// when the column is constant.
struct OuterEdges {
  double lo = 0.0;
  double hi = 0.0;
};

[[nodiscard]] inline OuterEdges numpy_outer_edges(double min_value, double max_value) {
  if (min_value == max_value) return {min_value - 0.5, max_value + 0.5};
  return {min_value, max_value};
}

/// `numpy.linspace(lo, hi, bins + 1)`, as `numpy.histogram` calls it: e_k = k * step + lo with the
/// product rounded before the addition (numpy multiplies the whole `arange` in place, then adds),
/// and the last edge set to `hi` exactly. A zero step (a range of denormals) takes numpy's
/// `(k / bins) * delta` branch.
class LinspaceEdges {
 public:
  LinspaceEdges(const OuterEdges& range, Eigen::Index bins)
      : range_(range),
        bins_(bins),
        div_(static_cast<double>(bins)),
        delta_(range.hi - range.lo),
        step_(delta_ / div_) {}

  /// e_k, k in [0, bins].
  [[nodiscard]] double operator()(Eigen::Index k) const {
    if (k == bins_) return range_.hi;
    if (step_ == 0.0) return mul_rounded(static_cast<double>(k) / div_, delta_) + range_.lo;
    return mul_rounded(static_cast<double>(k), step_) + range_.lo;
  }

 private:
  OuterEdges range_;
  Eigen::Index bins_;
  double div_;
  double delta_;
  double step_;
};

/// All bins + 1 edges into `edges`.
inline void numpy_histogram_edges(const OuterEdges& range, Eigen::Index bins, double* edges) {
  const LinspaceEdges edge(range, bins);
  for (Eigen::Index k = 0; k <= bins; ++k) edges[k] = edge(k);
}

/// A first guess of a value's bin from its position in the range, clamped to [0, top]. Only a
/// guess: the callers correct it against the actual edges, so the result never depends on the
/// rounding here (NaN and infinities land on a bound).
[[nodiscard]] inline Eigen::Index bin_guess(double x, double lo, double norm, Eigen::Index top) {
  const double f = (x - lo) * norm;
  if (!(f > 0.0)) return 0;
  if (f >= static_cast<double>(top)) return top;
  return static_cast<Eigen::Index>(f);
}

/// The bin numpy.histogram counts x in: e_c <= x < e_{c+1}, the last bin closed, for x in
/// [e_0, e_B] and non-decreasing edges. `c` is a guess in [0, B-1], walked to the exact bin.
/// (numpy computes floor((x - lo) * bins / (hi - lo)) and corrects it by one bin against the
/// edges; the two can differ only when bins are a few ULPs wide, where that estimate can be off by
/// more than one bin. They agree on every vector PyOD produced.)
[[nodiscard]] inline Eigen::Index count_bin(double x, const double* edges, Eigen::Index bins,
                                            Eigen::Index c) {
  while (c > 0 && x < edges[c]) --c;
  while (c < bins - 1 && edges[c + 1] <= x) ++c;
  return c;
}

/// `numpy.digitize(x, edges, right=True)` = #{k : e_k < x} in [0, B+1] for non-decreasing edges
/// (numpy's searchsorted, side="left"). `b` is a guess in [0, B+1], walked to the exact answer.
[[nodiscard]] inline Eigen::Index digitize_right(double x, const double* edges, Eigen::Index bins,
                                                 Eigen::Index b) {
  while (b > 0 && !(edges[b - 1] < x)) --b;
  while (b <= bins && edges[b] < x) ++b;
  return b;
}

/// numpy's pairwise summation of n doubles spaced `stride` apart (`pairwise_sum_DOUBLE`):
/// a plain loop below 8 terms, eight interleaved partial sums up to 128, halves above that (the
/// split rounded down to a multiple of 8). np.sum(axis=...) adds the result to its identity 0,
/// which changes nothing.
[[nodiscard]] inline double numpy_pairwise_sum(const double* a, Eigen::Index n,
                                               Eigen::Index stride) {
  if (n < 8) {
    double res = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) res += a[i * stride];
    return res;
  }
  if (n <= 128) {
    double r[8];
    for (Eigen::Index k = 0; k < 8; ++k) r[k] = a[k * stride];
    Eigen::Index i = 8;
    for (; i < n - (n % 8); i += 8) {
      for (Eigen::Index k = 0; k < 8; ++k) r[k] += a[(i + k) * stride];
    }
    double res = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]));
    for (; i < n; ++i) res += a[i * stride];
    return res;
  }
  Eigen::Index n2 = n / 2;
  n2 -= n2 % 8;
  return numpy_pairwise_sum(a, n2, stride) + numpy_pairwise_sum(a + n2 * stride, n - n2, stride);
}

/// numpy_pairwise_sum of d terms per row for many rows, the terms given one index at a time
/// (term k of every row, then term k + 1): the same bits as numpy_pairwise_sum over each row's d
/// terms, without holding them. The recursion's shape depends on d only, so its leaves (runs of
/// at most 128 terms) are summed as the terms arrive, with numpy's eight partial sums, and each
/// finished leaf is pushed on a stack whose top two are added whenever a split closes. Memory per
/// row: nine partial sums and one per level of the split (about log2(d / 64)).
class PairwiseRowSums {
 public:
  /// Sums of `terms` terms (>= 1) for each of `rows` rows.
  PairwiseRowSums(Eigen::Index terms, Eigen::Index rows) : terms_(terms), rows_(rows) {
    plan(terms);
    partial_.assign(static_cast<std::size_t>(rows * 9), 0.0);
  }

  [[nodiscard]] Eigen::Index rows() const { return rows_; }
  /// Terms added per row so far.
  [[nodiscard]] Eigen::Index added() const { return added_; }

  /// Adds the next term of every row: t[i] for row i.
  void add(const double* t) {
    require(added_ < terms_, "pairwise sums: all ", terms_, " terms were added");
    const Leaf& leaf = leaves_[leaf_];
    const Eigen::Index s = leaf.size;
    const Eigen::Index k = in_leaf_;
    const auto n = static_cast<std::size_t>(rows_);
    double* res = partial_.data() + 8 * n;  // r[0..7] of row i at partial_[q * n + i]
    if (s < 8) {
      if (k == 0) std::fill_n(res, n, 0.0);
      for (std::size_t i = 0; i < n; ++i) res[i] += t[i];
    } else if (k < 8) {
      std::copy_n(t, n, partial_.data() + static_cast<std::size_t>(k) * n);
    } else if (k < s - s % 8) {
      double* r = partial_.data() + static_cast<std::size_t>(k % 8) * n;
      for (std::size_t i = 0; i < n; ++i) r[i] += t[i];
    } else {
      if (k == s - s % 8) combine(res);
      for (std::size_t i = 0; i < n; ++i) res[i] += t[i];
    }
    ++added_;
    if (++in_leaf_ < s) return;
    if (s >= 8 && s % 8 == 0) combine(res);
    stack_.insert(stack_.end(), res, res + n);
    for (int a = 0; a < leaf.merges; ++a) {
      // right = top, left = below it: left + right, as numpy returns it.
      double* right = stack_.data() + stack_.size() - n;
      double* left = right - n;
      for (std::size_t i = 0; i < n; ++i) left[i] += right[i];
      stack_.resize(stack_.size() - n);
    }
    ++leaf_;
    in_leaf_ = 0;
  }

  /// The sums, once every term has been added: sum(i) of row i.
  [[nodiscard]] double sum(Eigen::Index i) const {
    require(added_ == terms_, "pairwise sums: ", added_, " of ", terms_, " terms added");
    return stack_[static_cast<std::size_t>(i)];
  }

 private:
  struct Leaf {
    Eigen::Index size;  // terms in this leaf
    int merges;         // splits that close after it
  };

  // The leaves of numpy_pairwise_sum(n) in order (post-order: a split's merge follows its
  // right half's last leaf).
  void plan(Eigen::Index n) {
    if (n <= 128) {
      leaves_.push_back({n, 0});
      return;
    }
    Eigen::Index n2 = n / 2;
    n2 -= n2 % 8;
    plan(n2);
    plan(n - n2);
    ++leaves_.back().merges;
  }

  // res = numpy's combination of the eight partial sums.
  void combine(double* res) const {
    const auto n = static_cast<std::size_t>(rows_);
    const double* r = partial_.data();
    for (std::size_t i = 0; i < n; ++i) {
      res[i] = ((r[i] + r[n + i]) + (r[2 * n + i] + r[3 * n + i])) +
               ((r[4 * n + i] + r[5 * n + i]) + (r[6 * n + i] + r[7 * n + i]));
    }
  }

  Eigen::Index terms_, rows_;
  std::vector<Leaf> leaves_;
  std::vector<double> partial_;  // 8 partial sums and the leaf's running sum, per row
  std::vector<double> stack_;    // finished halves, rows_ values each
  std::size_t leaf_ = 0;
  Eigen::Index in_leaf_ = 0, added_ = 0;
};

// ---- exact order statistics without sorting ----------------------------------------------------

/// Counts #{x < e} for many e over one column, exactly, in O(1) expected time per query.
///
/// The values are bucketed (not sorted) into equal cells over [lo, hi], 4 to 8 values per cell.
/// cell(v) is monotone in v, so every value in a cell below cell(e) is < e and every value in a
/// cell above is > e: the answer is the number of values in the cells below plus a count inside
/// cell(e), by a scan when the cell is small and by binary search in it (sorted once) when it is
/// not. So exactness rests on monotonicity alone, not on how cell() rounds, and heavily tied or
/// heavy-tailed data degrade to O(n log n), never worse.
///
/// Bucketing is two counting-sort passes (256 coarse cells, then the fine cells inside each
/// coarse one) so that every scatter stays within cache; only values move, cells are recomputed.
template <class Scalar>
class BucketedColumn {
 public:
  void reset(const Scalar* column, Eigen::Index stride, Eigen::Index n, double lo, double hi) {
    // Fine cells per coarse cell: a power of two, so that coarse = fine >> shift.
    int shift = 0;
    while ((Eigen::Index{4} * kCoarse << (shift + 1)) <= n) ++shift;
    const Eigen::Index per_coarse = Eigen::Index{1} << shift;
    shift_ = shift;
    lo_ = lo;
    scale_ = static_cast<double>(kCoarse * per_coarse) / (hi - lo);
    if (!std::isfinite(scale_)) scale_ = 0.0;  // a range of denormals: one cell
    // Values lie in [lo, hi], where value_cell() is monotone, so cells = value_cell(hi) + 1 bounds
    // them (rounding may add one cell past the nominal count) without a clamp.
    cells_ = value_cell(hi) + 1;
    coarse_cells_ = ((cells_ - 1) >> shift) + 1;
    const auto size = static_cast<std::size_t>(n);

    // Pass 1: the coarse histogram.
    coarse_start_.assign(static_cast<std::size_t>(coarse_cells_ + 1), 0);
    for (Eigen::Index i = 0; i < n; ++i) {
      ++coarse_start_[static_cast<std::size_t>(
          (value_cell(static_cast<double>(column[i * stride])) >> shift) + 1)];
    }
    for (std::size_t k = 1; k < coarse_start_.size(); ++k) coarse_start_[k] += coarse_start_[k - 1];

    // Pass 2: scatter the values into their coarse cells.
    cursor_.assign(coarse_start_.begin(), coarse_start_.end() - 1);
    staged_.resize(size);
    for (Eigen::Index i = 0; i < n; ++i) {
      const Scalar x = column[i * stride];
      staged_[static_cast<std::size_t>(
          cursor_[static_cast<std::size_t>(value_cell(static_cast<double>(x)) >> shift)]++)] = x;
    }

    // Pass 3: inside each coarse cell, a counting sort by fine cell.
    start_.assign(static_cast<std::size_t>(cells_ + 1), 0);
    values_.resize(size);
    for (Eigen::Index k = 0; k < coarse_cells_; ++k) {
      const Eigen::Index first = coarse_start_[static_cast<std::size_t>(k)];
      const Eigen::Index last = coarse_start_[static_cast<std::size_t>(k + 1)];
      const Eigen::Index base = k * per_coarse;
      const Eigen::Index fine = std::min(per_coarse, cells_ - base);  // the last may be short
      Eigen::Index* start = start_.data() + base;  // this coarse cell's fine starts
      for (Eigen::Index i = first; i < last; ++i) {
        ++start[value_cell(static_cast<double>(staged_[static_cast<std::size_t>(i)])) - base + 1];
      }
      start[0] = first;  // (start[fine] is the next coarse cell's start[0], set in its turn)
      for (Eigen::Index t = 1; t < fine; ++t) start[t] += start[t - 1];
      cursor_.assign(start, start + fine);
      for (Eigen::Index i = first; i < last; ++i) {
        const Scalar x = staged_[static_cast<std::size_t>(i)];
        const auto t = static_cast<std::size_t>(value_cell(static_cast<double>(x)) - base);
        values_[static_cast<std::size_t>(cursor_[t]++)] = x;
      }
    }
    start_[static_cast<std::size_t>(cells_)] = n;

    for (std::size_t c = 0; c + 1 < start_.size(); ++c) {
      if (start_[c + 1] - start_[c] > kScanLimit) {
        std::sort(values_.begin() + start_[c], values_.begin() + start_[c + 1]);
      }
    }
  }

  /// The number of coarse cells (256, or 257 when rounding puts the maximum one past).
  [[nodiscard]] Eigen::Index coarse_cells() const { return coarse_cells_; }

  /// The coarse cell of e, in [0, coarse_cells()); monotone in e. Queries grouped by coarse cell
  /// touch one cache-sized slice of the column.
  [[nodiscard]] Eigen::Index coarse_cell(double e) const { return cell(e) >> shift_; }

  /// #{values < e}.
  [[nodiscard]] Eigen::Index count_below(double e) const {
    const auto c = static_cast<std::size_t>(cell(e));
    const Eigen::Index first = start_[c];
    const Eigen::Index last = start_[c + 1];
    const Scalar* v = values_.data();
    if (last - first <= kScanLimit) {
      Eigen::Index below = first;
      for (Eigen::Index i = first; i < last; ++i) below += static_cast<double>(v[i]) < e ? 1 : 0;
      return below;
    }
    return static_cast<Eigen::Index>(
        std::lower_bound(v + first, v + last, e,
                         [](Scalar x, double edge) { return static_cast<double>(x) < edge; }) -
        v);
  }

 private:
  static constexpr Eigen::Index kCoarse = 256;
  static constexpr Eigen::Index kScanLimit = 64;

  /// Cell of a value of the column (in [lo, hi]): no clamp needed, see reset().
  [[nodiscard]] Eigen::Index value_cell(double v) const {
    return static_cast<Eigen::Index>((v - lo_) * scale_);
  }
  /// Cell of any query, clamped to the cells; equal to value_cell() on [lo, hi], so monotone.
  [[nodiscard]] Eigen::Index cell(double v) const { return bin_guess(v, lo_, scale_, cells_ - 1); }

  int shift_ = 0;
  double lo_ = 0.0;
  double scale_ = 0.0;
  Eigen::Index cells_ = 1;
  Eigen::Index coarse_cells_ = 1;
  std::vector<Eigen::Index> start_;  // first position of each fine cell in values_, then n
  std::vector<Eigen::Index> coarse_start_;
  std::vector<Eigen::Index> cursor_;
  std::vector<Scalar> staged_;  // values grouped by coarse cell
  std::vector<Scalar> values_;  // grouped by fine cell; cells above kScanLimit sorted
};

/// PyOD's threshold_: numpy.percentile(scores, 100 (1 - contamination)), method "linear",
/// bit-identical to numpy (the same result as hbos::compute_threshold with Contamination).
template <class Scalar>
[[nodiscard]] Scalar pyod_threshold(const Scalar* scores, Eigen::Index n, double contamination,
                                    std::vector<Scalar>& scratch) {
  const double q = (100.0 * (1.0 - contamination)) / 100.0;
  return numpy_percentile_linear(scores, static_cast<std::size_t>(n), q, scratch);
}

/// Reusable buffers for pyod_optimal_bins.
template <class Scalar>
struct AutoBinsScratch {
  BucketedColumn<Scalar> column;
  std::vector<Eigen::Index> below;  // #{x < e_k} of every interior edge of every candidate b
  std::vector<Eigen::Index> next_k;
  std::vector<double> next_edge;
  std::vector<Eigen::Index> next_coarse;
  std::vector<double> terms;
};

/// PyOD's `get_optimal_n_bins` (Birgé–Rozenblac as PyOD writes it) for one column:
///
///     L(b) = sum_{k<b} [ N_k ln(b N_k / n + 1) - (b - 1 + (ln b)^2.5) ],   b = 1 .. floor(sqrt(n))
///     - 1
///
/// with N_k the counts of numpy.histogram(x, b); returns the first argmax. The penalty sits inside
/// the sum (so it is paid b times) and the `+ 1` is PyOD's epsilon. Each term is rounded as numpy
/// rounds it (product, then difference) and the b terms are summed pairwise, as np.sum does.
///
/// Cost: the column is bucketed once (O(n)); every interior edge of every candidate, about n / 2
/// of them, is then located in O(1) expected time, visiting the edges coarse cell by coarse cell
/// (a merge of the candidates' sorted edge lists) so that the column is read once, in order.
/// PyOD re-histograms the column for every b: O(n sqrt(n)).
/// `min_value`/`max_value` are the column's extremes; requires n >= 4 and no NaN.
template <class Scalar>
[[nodiscard]] Eigen::Index pyod_optimal_bins(const Scalar* column, Eigen::Index stride,
                                             Eigen::Index n, double min_value, double max_value,
                                             AutoBinsScratch<Scalar>& scratch) {
  const OuterEdges range = numpy_outer_edges(min_value, max_value);
  BucketedColumn<Scalar>& sorted = scratch.column;
  sorted.reset(column, stride, n, range.lo, range.hi);
  // int(np.sqrt(n)): the sqrt of a double, truncated. Candidates are b = 1 .. last.
  const Eigen::Index last = static_cast<Eigen::Index>(std::sqrt(static_cast<double>(n))) - 1;
  // Interior edge k (1 <= k < b) of candidate b is stored at row(b) + k - 1.
  auto row = [](Eigen::Index b) { return (b - 1) * (b - 2) / 2; };
  scratch.below.resize(static_cast<std::size_t>(row(last + 1)));
  scratch.next_k.assign(static_cast<std::size_t>(last + 1), 1);
  scratch.next_edge.resize(static_cast<std::size_t>(last + 1));
  scratch.next_coarse.resize(static_cast<std::size_t>(last + 1));
  for (Eigen::Index b = 2; b <= last; ++b) {
    const double e = LinspaceEdges(range, b)(1);
    scratch.next_edge[static_cast<std::size_t>(b)] = e;
    scratch.next_coarse[static_cast<std::size_t>(b)] = sorted.coarse_cell(e);
  }
  for (Eigen::Index cell = 0; cell < sorted.coarse_cells(); ++cell) {
    for (Eigen::Index b = 2; b <= last; ++b) {
      const auto ub = static_cast<std::size_t>(b);
      Eigen::Index& k = scratch.next_k[ub];
      if (k >= b || scratch.next_coarse[ub] > cell) continue;
      const LinspaceEdges edge(range, b);
      while (k < b && scratch.next_coarse[ub] <= cell) {
        scratch.below[static_cast<std::size_t>(row(b) + k - 1)] =
            sorted.count_below(scratch.next_edge[ub]);
        if (++k < b) {
          scratch.next_edge[ub] = edge(k);
          scratch.next_coarse[ub] = sorted.coarse_cell(scratch.next_edge[ub]);
        }
      }
    }
  }

  const double n_double = static_cast<double>(n);
  Eigen::Index best_bins = 1;
  double best = -std::numeric_limits<double>::infinity();
  for (Eigen::Index b = 1; b <= last; ++b) {
    scratch.terms.resize(static_cast<std::size_t>(b));
    const double penalty =
        static_cast<double>(b - 1) + std::pow(std::log(static_cast<double>(b)), 2.5);
    Eigen::Index previous = 0;  // #{x < e_0}: e_0 is the minimum
    for (Eigen::Index k = 0; k < b; ++k) {
      // Bin k holds e_k <= x < e_{k+1}; the last bin is closed and ends at the maximum.
      const Eigen::Index next =
          k + 1 == b ? n : std::max(previous, scratch.below[static_cast<std::size_t>(row(b) + k)]);
      const Eigen::Index count = next - previous;
      previous = next;
      // 0 * ln(0 / n + 1) is exactly 0, so the log can be skipped for empty bins.
      const double weighted =
          count == 0 ? 0.0
                     : mul_rounded(static_cast<double>(count),
                                   std::log(static_cast<double>(b * count) / n_double + 1.0));
      scratch.terms[static_cast<std::size_t>(k)] = weighted - penalty;
    }
    const double likelihood = numpy_pairwise_sum(scratch.terms.data(), b, 1);
    if (likelihood > best) {  // strict: np.argmax keeps the first maximum
      best = likelihood;
      best_bins = b;
    }
  }
  return best_bins;
}

}  // namespace hbos::detail
