#pragma once
/// \file
/// One feature's histogram: its bins, counts, and the contribution each bin adds to a score.
///
/// Maths. With bin heights h_k = count_k / width_k (a density up to a constant) and
/// h_max = max_k h_k, a value x falling in bin k contributes
///
///     c(x) = log(h_max / h_k)                                   (Goldstein & Dengel 2012, eq. 1)
///
/// which is 0 in the modal bin and grows as the bin gets sparser. Heights are normalised by the
/// feature's own maximum, so every feature weighs the same and shifting or rescaling a feature
/// changes nothing (PyOD's `log2(density + alpha)` lacks both properties; see hbos/pyod/model.hpp).
///
/// Rules that make every score finite and documented:
/// - **Empty bins** score as if they held `empty_bin_count` samples (default 0.5, less than any
///   observed bin): c = log(h_max * width_k / empty_bin_count).
/// - **Outside the fitted range** at scoring time: within `range_tolerance` bin widths of the
///   edge a value scores as the edge bin; beyond it, it gets the feature's **cap**,
///   log(h_max * max_k width_k / empty_bin_count), the largest contribution any value can get.
/// - **Constant feature** (min == max under EqualWidth/EqualFrequency): one bin of width 0; its
///   value contributes 0, any other value the cap log(n / empty_bin_count).
/// - **Tails** (binning.hpp, Tail): Upper zeroes contributions at or below the modal bin and
///   makes them non-decreasing above it; values below the range contribute 0. Lower mirrors it.
/// - **Periodic** features wrap modulo the period; the first and last bins are neighbours and a
///   value never falls out of range.
///
/// Interval convention: bin k holds [e_k, e_{k+1}), the last bin is closed. Counting and lookup
/// call the same `bin_of`, so a training value is always scored from the bin it was counted in.
///
/// Speed: fitting reads the column twice (a fused min/max/finiteness pass, then a counting pass:
/// up to 16 bins by vector compares of one-byte indices, beyond that into four interleaved
/// sub-histograms so increments of one bin do not wait on each other);
/// scoring is one pass of a subtract, a multiply, a truncation and a table lookup per value, with
/// every out-of-range or non-finite value diverted to a slow path. Columns with direct access
/// (matrices, maps, blocks, row-major maps) are read in place through their stride.
///
/// Threading: a fitted Histogram is immutable through its const interface; concurrent const
/// calls are safe. `refit` is the (non-const) reuse path of Workspace.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "hbos/binning.hpp"
#include "hbos/detail/byte_bins.hpp"
#include "hbos/detail/scaling.hpp"
#include "hbos/error.hpp"
#include "hbos/histogram_parts.hpp"

namespace hbos {

/// Scoring rules shared by every feature of a model.
struct ScoringOptions {
  double empty_bin_count = 0.5;  ///< an empty bin scores as if it held this many samples, in (0, 1]
  double range_tolerance =
      0.5;  ///< [bins] beyond the fitted range, within this many widths: edge bin
};

namespace detail {

inline void validate(const ScoringOptions& o) {
  require(o.empty_bin_count > 0.0 && o.empty_bin_count <= 1.0,
          "empty_bin_count must lie in (0, 1], got ", o.empty_bin_count);
  require(o.range_tolerance >= 0.0 && std::isfinite(o.range_tolerance),
          "range_tolerance must be finite and >= 0, got ", o.range_tolerance);
}

}  // namespace detail

/// A fitted one-feature histogram. See the file comment for the maths and the rules.
template <class Scalar>
class Histogram {
  static_assert(std::is_floating_point_v<Scalar>, "Histogram needs float or double");

 public:
  using Index = Eigen::Index;

  /// Number of bins, >= 1 once fitted (fine bins when shifts > 1).
  [[nodiscard]] Index bins() const { return static_cast<Index>(counts_.size()); }
  /// bins() + 1 edges, ascending; bin k is [edges[k], edges[k+1]).
  [[nodiscard]] const std::vector<Scalar>& edges() const { return layout_.edges; }
  /// Training samples counted in each bin.
  [[nodiscard]] const std::vector<Index>& counts() const { return counts_; }
  /// The contribution of a value in each bin, after the tail rule (>= 0, 0 in the modal bin).
  [[nodiscard]] const std::vector<Scalar>& bin_contributions() const { return contribution_; }
  /// The largest contribution any value can get (out of range, or an empty bin).
  [[nodiscard]] Scalar cap() const { return cap_; }
  [[nodiscard]] bool periodic() const { return periodic_; }
  [[nodiscard]] Tail tail() const { return tail_; }
  /// The fitted range [lower(), upper()] (the period for a periodic feature).
  [[nodiscard]] Scalar lower() const { return layout_.lo; }
  [[nodiscard]] Scalar upper() const { return layout_.hi; }
  /// Index of the modal (densest) bin; the first one on ties.
  [[nodiscard]] Index mode() const { return mode_; }

  /// The bin a value falls in. Periodic features wrap; other values are clamped into
  /// [lower(), upper()] first, so out-of-range values map to the edge bins.
  [[nodiscard]] Index bin_of(Scalar x) const {
    if (periodic_) return uniform_bin(wrap(x));
    return in_range_bin(std::clamp(x, layout_.lo, layout_.hi));
  }

  /// The contribution of value `x` to a sample's score (see the file comment). `x` must be finite.
  [[nodiscard]] Scalar contribution(Scalar x) const {
    if (periodic_) return contribution_[static_cast<std::size_t>(uniform_bin(wrap(x)))];
    if (x < layout_.lo) return x >= tolerance_lo_ ? contribution_.front() : below_;
    if (x > layout_.hi) return x <= tolerance_hi_ ? contribution_.back() : above_;
    return contribution_[static_cast<std::size_t>(in_range_bin(x))];
  }

  /// Contributions of a whole column: out[i] = contribution(x[i]) (or += with `accumulate`).
  /// Throws naming X(i, feature) on a non-finite value.
  void contributions_into(const detail::ColumnView<Scalar>& x, Scalar* out, bool accumulate,
                          Index feature = 0) const;

  /// Pre-grows storage for up to `bins` bins, so refits up to that size do not allocate.
  void reserve(Index bins) {
    detail::require(bins >= 0 && bins <= kMaxBinsLimit, "Histogram::reserve: bins must lie in [0, ",
                    kMaxBinsLimit, "], got ", bins);
    rule_scratch_.sums.reserve(static_cast<std::size_t>(2 * bins + 1));
    layout_.edges.reserve(static_cast<std::size_t>(bins + 1));
    counts_.reserve(static_cast<std::size_t>(bins));
    contribution_.reserve(static_cast<std::size_t>(bins));
    rule_scratch_.cells.reserve(static_cast<std::size_t>(4 * bins));
  }

  /// Frees the buffers only fitting needs (a fitted model keeps just what scoring reads).
  void release_fit_buffers() {
    std::vector<std::int64_t>().swap(rule_scratch_.sums);
    std::vector<std::uint32_t>().swap(rule_scratch_.cells);
    detail::ScratchDoubles().swap(rule_scratch_.values);
  }

  /// The parts this histogram is built from (hbos/histogram_parts.hpp): what model files store
  /// and merged fits add up.
  [[nodiscard]] HistogramParts<Scalar> parts() const {
    HistogramParts<Scalar> p;
    p.edges = layout_.edges;
    p.counts = counts_;
    p.lo = layout_.lo;
    p.hi = layout_.hi;
    p.inv_width = layout_.inv_width;
    p.period = layout_.period;
    p.scale = layout_.scale;
    p.base = layout_.base;
    p.shifts = shifts_;
    p.tail = tail_;
    p.periodic = periodic_;
    p.uniform = uniform_;
    p.fine = layout_.fine;
    return p;
  }

  /// Rebuilds a fitted histogram from its parts, deriving the contributions with the code `fit`
  /// uses (the sample count is the sum of the counts): `from_parts(h.parts(), options)` scores
  /// bit for bit like `h` when `options` are the ones `h` was fitted with.
  /// \throws InvalidArgument when the parts break their invariant (messages start with `where`).
  [[nodiscard]] static Histogram from_parts(HistogramParts<Scalar> parts,
                                            const ScoringOptions& options,
                                            const std::string& where = "histogram") {
    detail::validate_parts(parts, where);
    detail::validate(options);
    Histogram h;
    // Counts are non-negative (validated above); a damaged file can still make their sum
    // overflow, which must be an error, not undefined behaviour.
    Index n = 0;
    for (const Index c : parts.counts) {
      detail::require(c <= std::numeric_limits<Index>::max() - n, where,
                      ": the counts add up to more than ", std::numeric_limits<Index>::max());
      n += c;
    }
    detail::require(n > 0, where, ": the counts add up to no samples");
    h.layout_.edges = std::move(parts.edges);
    h.layout_.lo = parts.lo;
    h.layout_.hi = parts.hi;
    h.layout_.inv_width = parts.inv_width;
    h.layout_.period = parts.period;
    h.layout_.scale = parts.scale;
    h.layout_.base = parts.base;
    h.layout_.fine = parts.fine;
    h.counts_ = std::move(parts.counts);
    h.shifts_ = parts.shifts;
    h.tail_ = parts.tail;
    h.periodic_ = parts.periodic;
    h.uniform_ = parts.uniform;
    h.score_bins(n, options);
    return h;
  }

  /// Re-fits this histogram to `column` in place, reusing its storage and `scratch`: no heap
  /// allocation once the buffers have grown to the sizes needed. `feature` labels errors.
  ///
  /// With `bin_index` (room for column.size() entries), the bin each training value was counted
  /// in is recorded there when the binning allows it cheaply (equal or fixed width, not
  /// periodic, every bin index representable as a BinIndex); the return value says whether it
  /// was. Scoring the training values from those indices then needs no lookup at all
  /// (Hbos::fit_and_score and the Workspace do this).
  /// \throws InvalidArgument if the column is empty or holds a non-finite value.
  template <class Column, class BinIndex = std::uint32_t>
  bool refit(const Column& column, const FeatureSpec& spec, const ScoringOptions& options,
             std::vector<Scalar>& scratch, Index feature = 0, BinIndex* bin_index = nullptr) {
    static_assert(std::is_integral_v<BinIndex> && std::is_unsigned_v<BinIndex>,
                  "bin indices are unsigned integers");
    const detail::ColumnView<Scalar> view = detail::view_of(column, scratch);
    return refit_view(view, spec, options, scratch, feature, bin_index);
  }

  /// Whether `spec` bins from its range alone (equal or fixed width, a fixed bin count, not
  /// periodic): what a staged fit needs, and all it reads of the data.
  [[nodiscard]] static bool fits_from_range(const FeatureSpec& spec) {
    const Binning& b = spec.binning;
    return !spec.periodic &&
           (b.method == BinningMethod::FixedWidth ||
            (b.method == BinningMethod::EqualWidth && b.rule == BinCountRule::Fixed));
  }

  /// The staged form of `refit` for specs with fits_from_range(): `begin_staged_fit` places the
  /// edges from the column's known finite range [lo, hi] (the ones refit would place), then
  /// `count_more` counts any split of the column into consecutive parts (recording bin indices
  /// like refit when the first call said it may), then `end_staged_fit` scores the bins of the n
  /// values counted. The result is bitwise refit's. Row-major fits use it to count every feature
  /// per block of rows, reading the matrix once instead of once per feature.
  /// \returns whether BinIndex can hold every bin index (so count_more may record them).
  template <class BinIndex>
  bool begin_staged_fit(Scalar lo, Scalar hi, const FeatureSpec& spec,
                        const ScoringOptions& options, std::vector<Scalar>& scratch,
                        Index feature) {
    detail::validate(spec, feature);
    detail::validate_for_scalar<Scalar>(spec, feature);
    detail::validate(options);
    detail::require(fits_from_range(spec), "feature ", feature,
                    ": a staged fit needs equal-width bins of a fixed count or fixed-width bins, "
                    "not periodic");
    periodic_ = false;
    tail_ = spec.tail;
    layout_.period = 0;
    shifts_ = spec.binning.shifts;
    uniform_ = true;
    // Equal- and fixed-width placement reads only the extremes (as ShardedFit relies on).
    const std::array<Scalar, 2> extremes{lo, hi};
    detail::place_uniform_edges(detail::ColumnView<Scalar>{extremes.data(), 2, 1}, spec, shifts_,
                                scratch, rule_scratch_, feature, layout_);
    counts_.assign(layout_.edges.size() - 1, 0);
    return layout_.edges.size() - 2 <=
           static_cast<std::size_t>(std::numeric_limits<BinIndex>::max());
  }
  /// Counts the next consecutive part of the column (every value finite, within [lo, hi]).
  template <class BinIndex>
  void count_more(const detail::ColumnView<Scalar>& part, BinIndex* bin_index) {
    accumulate_counts(part, bin_index);
  }
  /// Scores the bins once all `n` values have been counted.
  void end_staged_fit(Index n, const ScoringOptions& options) { score_bins(n, options); }
  /// During a staged fit: whether count_more computes this histogram's bins with the one-byte
  /// kernel (detail/byte_bins.hpp: few equal-width bins, unscaled), and then its constants in
  /// `constants`. A caller may compute a part's bins itself with them, as that kernel does (two
  /// features of a row-major block at once), and count them with count_byte_bins: the counts
  /// are count_more's.
  [[nodiscard]] bool byte_bin_constants(detail::ByteBinConstants<Scalar>& constants) const {
    if (!counts_by_bytes()) return false;
    constants.lo = layout_.lo;
    constants.inv = layout_.inv_width;
    constants.last = static_cast<Scalar>(layout_.edges.size() - 2);
    return true;
  }
  /// Counts the one-byte bins `b[0, m)` (each below bins()) of the next part of a staged fit.
  void count_byte_bins(const std::uint8_t* b, std::size_t m) {
    std::array<std::uint64_t, detail::kCompareCountMaxBins> few{};
    const std::size_t k = counts_.size();
    detail::count_byte_indices(b, m, k, few.data());
    for (std::size_t j = 0; j < k; ++j) counts_[j] += static_cast<Index>(few[j]);
  }

 private:
  template <class BinIndex>
  bool refit_view(const detail::ColumnView<Scalar>& x, const FeatureSpec& spec,
                  const ScoringOptions& options, std::vector<Scalar>& scratch, Index feature,
                  BinIndex* bin_index);

  /// The offset of x into the period, in [0, period] (rounding may give exactly period: clamped
  /// to the last bin). Within a period of the start, x - start; further out (6e16 with a period
  /// of 2 pi, or a start of 1e300), x - start would lose x's position or t - period * floor(t /
  /// period) its accuracy, so each term is reduced by the exact fmod first.
  [[nodiscard]] Scalar wrap(Scalar x) const {
    const Scalar p = layout_.period;
    Scalar t = x - layout_.lo;
    if (t >= Scalar(0) && t < p) return t;
    t = std::fmod(std::fmod(x, p) - std::fmod(layout_.lo, p), p);  // |t| < p, exact but one sum
    return t < Scalar(0) ? t + p : t;
  }
  /// Uniform bins: the bin of offset t = (x * scale - base), clamped into [0, bins()) (NaN: 0).
  [[nodiscard]] Index uniform_bin(Scalar t) const {
    const Scalar u = t * layout_.inv_width;
    if (!(u > Scalar(0))) return 0;
    const Index last = bins() - 1;
    if (u >= static_cast<Scalar>(last)) return last;
    return static_cast<Index>(u);
  }
  [[nodiscard]] Scalar offset(Scalar x) const {
    return layout_.scale == Scalar(1) ? x - layout_.lo : x * layout_.scale - layout_.base;
  }
  [[nodiscard]] Index in_range_bin(Scalar x) const {
    if (uniform_) return uniform_bin(offset(x));
    // Irregular bins: the number of interior edges <= x.
    const auto first = layout_.edges.begin() + 1;
    const auto last = layout_.edges.end() - 1;
    return static_cast<Index>(std::upper_bound(first, last, x) - first);
  }

  template <class BinIndex = std::uint32_t>
  void count(const detail::ColumnView<Scalar>& x, BinIndex* bin_index = nullptr) {
    counts_.assign(layout_.edges.size() - 1, 0);
    accumulate_counts(x, bin_index);
  }
  /// Adds the counts of `x` to counts_ (sized to the bins), recording each value's bin.
  template <class BinIndex = std::uint32_t>
  void accumulate_counts(const detail::ColumnView<Scalar>& x, BinIndex* bin_index);
  /// Whether accumulate_counts takes the one-byte kernel: few uniform bins of a non-periodic,
  /// unscaled feature with a positive width.
  [[nodiscard]] bool counts_by_bytes() const {
    return !periodic_ && uniform_ && layout_.inv_width > Scalar(0) && layout_.scale == Scalar(1) &&
           layout_.edges.size() - 1 <= detail::kCompareCountMaxBins;
  }
  void smooth_counts();
  void score_bins(Index n, const ScoringOptions& options);

  detail::EdgeLayout<Scalar> layout_;
  std::vector<Index> counts_;
  std::vector<Scalar> contribution_;
  detail::RuleScratch rule_scratch_;  // fitting only: interleaved counting, the bin-count rules
  Scalar tolerance_lo_ = 0, tolerance_hi_ = 0;
  Scalar below_ = 0, above_ = 0;  // contributions beyond the tolerance band
  Scalar cap_ = 0;
  Index mode_ = 0;
  Index shifts_ = 1;  // averaged shifted histograms: fine bins per coarse bin
  Tail tail_ = Tail::Both;
  bool periodic_ = false;
  bool uniform_ = true;
};

// ---------------------------------------------------------------------------------------------
// Implementation
// ---------------------------------------------------------------------------------------------

template <class Scalar>
void Histogram<Scalar>::contributions_into(const detail::ColumnView<Scalar>& x, Scalar* out,
                                           bool accumulate, Index feature) const {
  // Local copies: the compiler cannot prove that stores to `out` leave the members unchanged and
  // would otherwise reload them after every store.
  const Scalar lo = layout_.lo, hi = layout_.hi, inv = layout_.inv_width;
  const Scalar* table = contribution_.data();
  const bool fast = uniform_ && inv > Scalar(0) && layout_.scale == Scalar(1) &&
                    bins() <= std::numeric_limits<std::int32_t>::max();
  // The exact path, for any value: the lookup of contribution(), throwing on non-finite values.
  auto exact = [&](Scalar v) {
    if (!std::isfinite(v)) detail::throw_not_finite(x, feature);
    return contribution(v);
  };
  detail::with_access(x, [&](auto at) {
    if (!fast) {
      for (Index i = 0; i < x.size; ++i) {
        const Scalar c = exact(at(i));
        out[i] = accumulate ? out[i] + c : c;
      }
      return;
    }
    // Uniform bins, a block at a time. A packet min/max scan of the block (in L1 by then) says
    // whether every value is finite and inside [lo, hi); such a block is scored by table loads,
    // with bin indices computed as counting computes them (in a loop the compiler vectorises).
    // A block with any other value takes the exact path, which gives the same contribution
    // wherever both apply (for v in [lo, hi) it is table[min(int(t), last)]).
    const auto last = static_cast<Scalar>(bins() - 1);
    constexpr Index block = 256;
    std::array<std::int32_t, block> b{};
    for (Index start = 0; start < x.size; start += block) {
      const Index m = std::min(block, x.size - start);
      const detail::MinMax<Scalar> range =
          detail::scan_min_max(detail::ColumnView<Scalar>{x.data + start * x.stride, m, x.stride});
      Scalar* o = out + start;
      if (range.finite && range.lo >= lo && range.hi < hi) {
        for (Index i = 0; i < m; ++i) {
          const Scalar u = (at(start + i) - lo) * inv;  // capped before truncating, as count() does
          b[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(u < last ? u : last);
        }
        if (accumulate) {
          for (Index i = 0; i < m; ++i) o[i] += table[b[static_cast<std::size_t>(i)]];
        } else {
          for (Index i = 0; i < m; ++i) o[i] = table[b[static_cast<std::size_t>(i)]];
        }
      } else {
        for (Index i = 0; i < m; ++i) {
          const Scalar c = exact(at(start + i));
          o[i] = accumulate ? o[i] + c : c;
        }
      }
    }
  });
}

template <class Scalar>
template <class BinIndex>
void Histogram<Scalar>::accumulate_counts(const detail::ColumnView<Scalar>& x,
                                          BinIndex* bin_index) {
  const Index n = x.size;
  const auto k = static_cast<std::size_t>(layout_.edges.size() - 1);
  if (periodic_) {
    // Periodic values arrive as offsets wrap(x) into the period: exactly what lookup computes.
    for (Index i = 0; i < n; ++i) ++counts_[static_cast<std::size_t>(uniform_bin(x[i]))];
    return;
  }
  constexpr auto int32_max = static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max());
  if (!uniform_ || !(layout_.inv_width > Scalar(0)) || layout_.scale != Scalar(1) ||
      k > int32_max) {
    for (Index i = 0; i < n; ++i) {
      const auto b = static_cast<std::size_t>(in_range_bin(x[i]));
      ++counts_[b];
      if (bin_index != nullptr) bin_index[i] = static_cast<BinIndex>(b);
    }
    return;
  }
  // Every value lies in [lo, hi] here. A block of bin indices is computed first, in a loop the
  // compiler vectorises: (v - lo) * inv, capped at the last bin in floating point (hi and
  // anything rounding past it belong to the last bin; capping before the truncation gives the
  // truncated value uniform_bin gives, and needs no integer min, which SSE2 lacks), truncated.
  const Scalar lo = layout_.lo, inv = layout_.inv_width;
  const auto last_bin = static_cast<Scalar>(k - 1);
  auto bin_at = [&](auto at, Index i) {
    const Scalar u = (at(i) - lo) * inv;
    return static_cast<std::int32_t>(u < last_bin ? u : last_bin);
  };
  constexpr Index block = 256;
  if (counts_by_bytes()) {
    // Few bins: the indices go to bytes (the caller's, when it records one-byte indices) and are
    // counted by comparison (detail/byte_bins.hpp).
    std::array<std::uint64_t, detail::kCompareCountMaxBins> few{};
    std::array<std::uint8_t, block> local{};
    std::array<Scalar, block> gathered{};
    detail::with_access(x, [&](auto at) {
      for (Index start = 0; start < n; start += block) {
        const Index m = std::min(block, n - start);
        const auto mm = static_cast<std::size_t>(m);
        std::uint8_t* b = local.data();
        if constexpr (sizeof(BinIndex) == 1) {
          if (bin_index != nullptr) b = reinterpret_cast<std::uint8_t*>(bin_index + start);
        }
        const Scalar* values = x.data + start;
        if (x.stride != 1) {
          // A strided column is gathered first: the block then takes the vector kernel too.
          for (Index i = 0; i < m; ++i) gathered[static_cast<std::size_t>(i)] = at(start + i);
          values = gathered.data();
        }
        detail::uniform_byte_bins(values, mm, lo, inv, last_bin, b);
        detail::count_byte_indices(b, mm, k, few.data());
        if constexpr (sizeof(BinIndex) != 1) {
          if (bin_index != nullptr)
            for (Index i = 0; i < m; ++i)
              bin_index[start + i] = static_cast<BinIndex>(b[static_cast<std::size_t>(i)]);
        }
      }
    });
    for (std::size_t j = 0; j < k; ++j) counts_[j] += static_cast<Index>(few[j]);
    return;
  }
  // More bins: counted into four interleaved sub-histograms, so that consecutive values in the
  // same bin increment different counters and the increments do not serialise.
  rule_scratch_.cells.assign(4 * k, 0);
  std::uint32_t* sub = rule_scratch_.cells.data();
  std::array<std::int32_t, block> b{};
  auto slot = [&](Index i, std::size_t lane) {
    return 4 * static_cast<std::size_t>(b[static_cast<std::size_t>(i)]) + lane;
  };
  detail::with_access(x, [&](auto at) {
    for (Index start = 0; start < n; start += block) {
      const Index m = std::min(block, n - start);
      for (Index i = 0; i < m; ++i) b[static_cast<std::size_t>(i)] = bin_at(at, start + i);
      const Index m4 = m - m % 4;
      for (Index i = 0; i < m4; i += 4) {
        ++sub[slot(i, 0)];
        ++sub[slot(i + 1, 1)];
        ++sub[slot(i + 2, 2)];
        ++sub[slot(i + 3, 3)];
      }
      for (Index i = m4; i < m; ++i) ++sub[slot(i, 0)];
      if (bin_index != nullptr) {
        for (Index i = 0; i < m; ++i)
          bin_index[start + i] = static_cast<BinIndex>(b[static_cast<std::size_t>(i)]);
      }
    }
  });
  for (std::size_t j = 0; j < k; ++j)
    counts_[j] += static_cast<Index>(sub[4 * j]) + sub[4 * j + 1] + sub[4 * j + 2] + sub[4 * j + 3];
}

template <class Scalar>
void Histogram<Scalar>::smooth_counts() {
  // Smoothed mass around each bin (averaged shifted histograms, Scott 1985): with m shifts the
  // fine bins are 1/m of a coarse bin and m_i = sum_{|d|<m} (1 - |d|/m) count_{i+d}, i.e. the
  // average of the m coarse histograms whose origins are shifted by one fine bin each. m = 1 is
  // the plain histogram. Periodic features wrap around. Stored in contribution_ for now.
  const auto k = counts_.size();
  const auto m = static_cast<std::ptrdiff_t>(shifts_);
  const auto kk = static_cast<std::ptrdiff_t>(k);
  // The direct sum costs k m: it serves every usual shift count (the default 25 fine bins x 5
  // costs 125 steps) bit for bit as it always has; beyond 2^20 steps (5 bins x 13107 shifts
  // would take 1e9) the same masses come from prefix sums in O(k + m), exactly in integers.
  if (static_cast<double>(kk) * static_cast<double>(m) <= 1048576.0) {
    for (std::ptrdiff_t i = 0; i < kk; ++i) {
      double mass = static_cast<double>(counts_[static_cast<std::size_t>(i)]);
      for (std::ptrdiff_t d = 1; d < m; ++d) {
        const double weight = 1.0 - static_cast<double>(d) / static_cast<double>(m);
        std::ptrdiff_t left = i - d, right = i + d;
        if (periodic_) {
          left = (left % kk + kk) % kk;
          right = right % kk;
        }
        if (left >= 0)
          mass += weight * static_cast<double>(counts_[static_cast<std::size_t>(left)]);
        if (right < kk)
          mass += weight * static_cast<double>(counts_[static_cast<std::size_t>(right)]);
      }
      contribution_[static_cast<std::size_t>(i)] = static_cast<Scalar>(mass);
    }
    return;
  }
  // sum_{|d|<m} (m - |d|) c_{i+d} = sum_{s<m} b_{i+s}, with the box sums b_u = sum_{t=u-m+1}^{u}
  // c_t (a triangle is a box convolved with a box); Q holds the prefix sums of b.
  auto count_at = [&](std::ptrdiff_t t) -> std::int64_t {
    if (periodic_) {
      t %= kk;
      if (t < 0) t += kk;
    } else if (t < 0 || t >= kk) {
      return 0;
    }
    return static_cast<std::int64_t>(counts_[static_cast<std::size_t>(t)]);
  };
  std::vector<std::int64_t>& q = rule_scratch_.sums;
  q.resize(static_cast<std::size_t>(kk + m));
  std::int64_t box = 0;
  for (std::ptrdiff_t t = 1 - m; t <= 0; ++t) box += count_at(t);
  q[0] = 0;
  for (std::ptrdiff_t u = 0; u + 1 < kk + m; ++u) {
    if (u > 0) box += count_at(u) - count_at(u - m);
    q[static_cast<std::size_t>(u + 1)] = q[static_cast<std::size_t>(u)] + box;
  }
  for (std::ptrdiff_t i = 0; i < kk; ++i) {
    const std::int64_t weighted =
        q[static_cast<std::size_t>(i + m)] - q[static_cast<std::size_t>(i)];
    contribution_[static_cast<std::size_t>(i)] =
        static_cast<Scalar>(static_cast<double>(weighted) / static_cast<double>(m));
  }
}

template <class Scalar>
void Histogram<Scalar>::score_bins(Index n, const ScoringOptions& options) {
  const auto k = counts_.size();
  contribution_.resize(k);
  const bool constant = !periodic_ && !(layout_.hi > layout_.lo);
  // log(a / b), also where a / b overflows (an empty_bin_count of 1e-308): log a - log b.
  auto log_ratio = [](double a, double b) {
    const double q = a / b;
    return std::isfinite(q) && q > 0.0 ? std::log(q) : std::log(a) - std::log(b);
  };
  if (constant) {
    std::fill(contribution_.begin(), contribution_.end(), Scalar(0));
    cap_ = static_cast<Scalar>(log_ratio(static_cast<double>(n), options.empty_bin_count));
    mode_ = 0;
  } else {
    smooth_counts();
    // Uniform bins share one nominal width: using it (not edge differences, which carry the
    // rounding of lo + j * width) keeps heights exactly proportional to mass, and scores exactly
    // invariant under affine maps of the feature.
    auto width_of = [&](std::size_t i) {
      return uniform_ ? 1.0
                      : static_cast<double>(layout_.edges[i + 1]) -
                            static_cast<double>(layout_.edges[i]);
    };
    // Heights h_i = mass_i / width_i, in double; only ratios to h_max matter. An empty
    // neighbourhood counts as `empty_bin_count` samples.
    auto height = [&](std::size_t i, bool regularise) {
      const double w = width_of(i);
      const double mass = static_cast<double>(contribution_[i]);
      return (regularise && !(mass > 0.0) ? options.empty_bin_count : mass) / w;
    };
    double h_max = 0.0;
    double w_max = 0.0;
    for (std::size_t i = 0; i < k; ++i) {
      const double h = height(i, false);
      if (h > h_max) {
        h_max = h;
        mode_ = static_cast<Index>(i);
      }
      w_max = std::max(w_max, width_of(i));
    }
    // Widths far from 1 (bins of subnormal or overflowing width) make the quotients overflow or
    // underflow: then every height is taken in logs instead.
    constexpr double w_lo = 0x1p-500, w_hi = 0x1p500;
    bool ordinary = std::isfinite(h_max) && h_max > 0.0 && w_max <= w_hi;
    for (std::size_t i = 0; ordinary && i < k; ++i) ordinary = width_of(i) >= w_lo;
    if (ordinary) {
      for (std::size_t i = 0; i < k; ++i)
        contribution_[i] = static_cast<Scalar>(std::max(0.0, log_ratio(h_max, height(i, true))));
      // The cap is at least every bin's contribution (with shifts, a bin's smoothed mass can be
      // below empty_bin_count).
      cap_ = static_cast<Scalar>(log_ratio(h_max * w_max, options.empty_bin_count));
    } else {
      auto log_width = [&](std::size_t i) {
        return detail::log_span(static_cast<double>(layout_.edges[i]),
                                static_cast<double>(layout_.edges[i + 1]));
      };
      auto log_height = [&](std::size_t i, bool regularise) {
        const double mass = static_cast<double>(contribution_[i]);
        if (!regularise && !(mass > 0.0)) return -std::numeric_limits<double>::infinity();
        return std::log(mass > 0.0 ? mass : options.empty_bin_count) - log_width(i);
      };
      double lh_max = -std::numeric_limits<double>::infinity();
      double lw_max = -std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < k; ++i) {
        const double lh = log_height(i, false);
        if (lh > lh_max) {
          lh_max = lh;
          mode_ = static_cast<Index>(i);
        }
        lw_max = std::max(lw_max, log_width(i));
      }
      for (std::size_t i = 0; i < k; ++i)
        contribution_[i] = static_cast<Scalar>(std::max(0.0, lh_max - log_height(i, true)));
      cap_ = static_cast<Scalar>(lh_max + lw_max - std::log(options.empty_bin_count));
    }
    for (std::size_t i = 0; i < k; ++i) cap_ = std::max(cap_, contribution_[i]);
  }

  // One-sided tails: zero on the good side of the mode, a running maximum on the anomalous side.
  const auto mode = static_cast<std::size_t>(mode_);
  if (tail_ == Tail::Upper) {
    std::fill(contribution_.begin(), contribution_.begin() + static_cast<std::ptrdiff_t>(mode) + 1,
              Scalar(0));
    for (std::size_t b = mode + 1; b < k; ++b)
      contribution_[b] = std::max(contribution_[b], contribution_[b - 1]);
  } else if (tail_ == Tail::Lower) {
    std::fill(contribution_.begin() + static_cast<std::ptrdiff_t>(mode), contribution_.end(),
              Scalar(0));
    for (std::size_t b = mode; b-- > 0;)
      contribution_[b] = std::max(contribution_[b], contribution_[b + 1]);
  }
  below_ = tail_ == Tail::Upper ? Scalar(0) : cap_;
  above_ = tail_ == Tail::Lower ? Scalar(0) : cap_;

  // The tolerance counts coarse bins (m fine bins each); a band beyond the range of Scalar
  // saturates (every value below the range is then within it).
  const auto tol =
      detail::saturate_cast<Scalar>(options.range_tolerance * static_cast<double>(shifts_));
  auto band = [&](Scalar w) { return tol == Scalar(0) ? Scalar(0) : tol * w; };
  tolerance_lo_ = layout_.lo - band(layout_.edges[1] - layout_.edges[0]);
  tolerance_hi_ = layout_.hi + band(layout_.edges[k] - layout_.edges[k - 1]);
}

template <class Scalar>
template <class BinIndex>
bool Histogram<Scalar>::refit_view(const detail::ColumnView<Scalar>& x, const FeatureSpec& spec,
                                   const ScoringOptions& options, std::vector<Scalar>& scratch,
                                   Index feature, BinIndex* bin_index) {
  const Index n = x.size;
  detail::require(n > 0, "feature ", feature, ": cannot fit a histogram to no samples");
  // Checked here, not only by Hbos: every user of a Histogram (the screen, the Workspace) gets
  // the same guarantees. A few comparisons per feature.
  detail::validate(spec, feature);
  detail::validate_for_scalar<Scalar>(spec, feature);
  detail::validate(options);
  periodic_ = spec.periodic;
  tail_ = spec.tail;
  layout_.period = 0;
  const bool equal_frequency = spec.binning.method == BinningMethod::EqualFrequency;
  shifts_ = equal_frequency ? 1 : spec.binning.shifts;

  if (!periodic_ && !equal_frequency) {
    // Equal or fixed width: the caller's column is read in place (min/max, then counting).
    uniform_ = true;
    detail::place_uniform_edges(x, spec, shifts_, scratch, rule_scratch_, feature, layout_);
    // Freedman–Diaconis reorders `scratch` in place: when `x` lives there, the order of the
    // counted values is no longer the caller's, so no indices are recorded.
    const bool in_order =
        x.data != scratch.data() || spec.binning.rule != BinCountRule::FreedmanDiaconis;
    const std::size_t last_bin = layout_.edges.size() - 2;  // edges were just placed
    const bool representable =
        last_bin <= static_cast<std::size_t>(std::numeric_limits<BinIndex>::max());
    const bool record = in_order && representable && bin_index != nullptr;
    count(x, record ? bin_index : static_cast<BinIndex*>(nullptr));
    score_bins(n, options);
    return record;
  }

  // Periodic features are binned as offsets into the period and equal-frequency bins need the
  // values sorted: both work on a copy in `scratch` (which may already hold the column).
  detail::finite_min_max(x, feature);
  if (x.data != scratch.data()) {
    scratch.resize(static_cast<std::size_t>(n));
    for (Index i = 0; i < n; ++i) scratch[static_cast<std::size_t>(i)] = x[i];
  }
  const detail::ColumnView<Scalar> values{scratch.data(), n, 1};
  if (periodic_) {
    uniform_ = true;
    layout_.lo = static_cast<Scalar>(spec.period_start);
    layout_.period = static_cast<Scalar>(spec.period);
    for (auto& v : scratch) v = wrap(v);  // offsets into the period; every rule is shift-invariant
    detail::place_uniform_edges(values, spec, shifts_, scratch, rule_scratch_, feature, layout_);
  } else {
    uniform_ = false;
    layout_.inv_width = 0;
    std::sort(scratch.begin(), scratch.end());
    const Index k = scratch.front() < scratch.back()
                        ? detail::rule_bins(values, spec.binning, scratch.front(), scratch.back(),
                                            scratch, rule_scratch_)
                        : 1;
    // rule_bins may reorder scratch (Freedman–Diaconis selects in place): sort again if so.
    if (spec.binning.rule == BinCountRule::FreedmanDiaconis)
      std::sort(scratch.begin(), scratch.end());
    detail::place_equal_frequency_edges(scratch.data(), n, k, layout_);
  }
  count(values, static_cast<BinIndex*>(nullptr));
  score_bins(n, options);
  return false;
}

}  // namespace hbos
