#pragma once
/// \file
/// The fitted HBOS model: one histogram per feature and the score they add up to.
///
///     score(x) = sum_j c_j(x_j),   c_j(v) = log(h_max_j / h_j(bin of v))
///
/// (Goldstein & Dengel 2012, eq. 1, with natural logs and heights normalised per feature; the
/// rules for empty bins, values out of range, constant features, one-sided tails and periodic
/// features are in histogram.hpp). Higher = more anomalous; a sample in every feature's modal bin
/// scores 0. Rows are samples, columns are features.
///
/// Inputs: any Eigen dense expression (matrices, maps, blocks; column-major data is read in place,
/// without copies), or a raw row-major buffer through the `*_row_major` overloads.
///
/// Threading: `Hbos` is immutable after `fit`; any number of threads may call its const members
/// concurrently.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "hbos/binning.hpp"
#include "hbos/error.hpp"
#include "hbos/histogram.hpp"

namespace hbos {

/// The default feature spec: 5 equal-width bins averaged over 5 shifted origins (ASH), two-sided.
///
/// Chosen by measurement (docs/accuracy.md): on the 17 ODDS sets (fit on all rows, no scaling)
/// its mean ROC-AUC is 0.7923, against 0.7798 for the classic 10 plain bins and 0.7896 for PyOD's
/// scale-dependent default; every (bins, shifts) in [4, 8] x [2, 8] lands within 0.79 +- 0.005,
/// so the choice is not a knife-edge. Scale- and shift-invariant like every equal-width spec.
[[nodiscard]] inline FeatureSpec default_feature() {
  FeatureSpec spec;
  spec.binning.method = BinningMethod::EqualWidth;
  spec.binning.rule = BinCountRule::Fixed;
  spec.binning.bins = 5;
  spec.binning.shifts = 5;
  return spec;
}

/// Parameters of a model: how each feature is binned and how bins are scored.
struct HbosParams {
  /// The spec of every feature that `features` does not override (default_feature()).
  FeatureSpec feature = default_feature();
  /// Optional per-feature specs; when non-empty its size must equal the feature count.
  std::vector<FeatureSpec> features{};
  /// Empty-bin and out-of-range rules shared by all features.
  ScoringOptions scoring{};

  /// The spec that applies to feature j.
  [[nodiscard]] const FeatureSpec& spec(Eigen::Index j) const {
    return features.empty() ? feature : features[static_cast<std::size_t>(j)];
  }
};

namespace detail {

inline void validate(const HbosParams& params, Eigen::Index n_features) {
  require(
      params.features.empty() || static_cast<Eigen::Index>(params.features.size()) == n_features,
      "params.features has ", params.features.size(), " specs but the data has ", n_features,
      " features");
  validate(params.scoring);
  for (Eigen::Index j = 0; j < n_features; ++j) validate(params.spec(j), j);
}

/// What a model requires of feature j's parts: counts adding up to `n_samples`,
/// flags agreeing with the feature's spec. \throws InvalidArgument naming the feature.
template <class Scalar>
void check_against_spec(const HistogramParts<Scalar>& p, const FeatureSpec& spec,
                        Eigen::Index n_samples, Eigen::Index j) {
  const bool equal_frequency = spec.binning.method == BinningMethod::EqualFrequency;
  // A saturating sum: a damaged file's counts must give an error, not an overflow.
  constexpr Eigen::Index kMost = std::numeric_limits<Eigen::Index>::max();
  Eigen::Index counted = 0;
  for (const Eigen::Index c : p.counts) {
    require(c >= 0, "feature ", j, ": its histogram has a negative count (", c, ")");
    counted = c > kMost - counted ? kMost : counted + c;
  }
  require(counted == n_samples, "feature ", j, ": its histogram counts ", counted,
          " samples, the model ", n_samples);
  require(p.periodic == spec.periodic && p.tail == spec.tail, "feature ", j,
          ": its histogram's periodic/tail flags disagree with its spec");
  require(p.uniform == (spec.periodic || !equal_frequency), "feature ", j,
          ": its histogram's bins are ", p.uniform ? "uniform" : "irregular",
          " but its spec's binning is not");
  require(p.shifts == (equal_frequency ? 1 : spec.binning.shifts), "feature ", j,
          ": its histogram has ", p.shifts, " shifts, its spec ", spec.binning.shifts);
}

/// Fits `histograms` (resized to the column count) to `x`, reusing their storage. Non-finite
/// values are caught by the fitting pass itself (no separate scan).
template <class Scalar, class Derived>
void fit_histograms(std::vector<Histogram<Scalar>>& histograms, const Eigen::DenseBase<Derived>& x,
                    const HbosParams& params, std::vector<Scalar>& scratch) {
  require(x.rows() > 0, "cannot fit to an empty data set (0 rows)");
  require(x.cols() > 0, "cannot fit to data with no features (0 columns)");
  validate(params, x.cols());
  histograms.resize(static_cast<std::size_t>(x.cols()));
  for (Eigen::Index j = 0; j < x.cols(); ++j)
    histograms[static_cast<std::size_t>(j)].refit(x.derived().col(j), params.spec(j),
                                                  params.scoring, scratch, j);
}

/// Scores every row of `x` into `scores` (n) and, when `contributions` is not null, each
/// feature's contribution into column j of the column-major n x d array it points to.
/// Non-finite values throw, naming X(i, j). `storage` holds columns without direct access.
template <class Scalar, class Derived>
void write_scores(const std::vector<Histogram<Scalar>>& histograms,
                  const Eigen::DenseBase<Derived>& x, Scalar* scores, Scalar* contributions,
                  std::vector<Scalar>& storage) {
  const Eigen::Index n = x.rows();
  if constexpr ((Derived::Flags & Eigen::DirectAccessBit) != 0) {
    if (contributions == nullptr) {
      // A block of rows at a time, every feature in turn: the block's running sums stay in L1
      // instead of streaming the score vector through memory once per feature.
      constexpr Eigen::Index block = 2048;
      for (Eigen::Index start = 0; start < n; start += block) {
        const Eigen::Index m = std::min(block, n - start);
        for (Eigen::Index j = 0; j < x.cols(); ++j) {
          ColumnView<Scalar> column = view_of(x.derived().col(j), storage);
          column.data += start * column.stride;
          column.size = m;
          histograms[static_cast<std::size_t>(j)].contributions_into(column, scores + start, j > 0,
                                                                     j);
        }
      }
      return;
    }
  }
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    const Histogram<Scalar>& h = histograms[static_cast<std::size_t>(j)];
    const ColumnView<Scalar> column = view_of(x.derived().col(j), storage);
    if (contributions == nullptr) {
      h.contributions_into(column, scores, j > 0, j);
      continue;
    }
    Scalar* c = contributions + j * n;
    h.contributions_into(column, c, false, j);
    if (j == 0) {
      std::copy(c, c + n, scores);
    } else {
      for (Eigen::Index i = 0; i < n; ++i) scores[i] += c[i];
    }
  }
}

/// Whether every feature's bin count is fixed by its spec alone and at most 256 (fine bins).
/// Runs before validation: must hold for any parameter values (a spec count that does not match,
/// bins x shifts that would overflow).
inline bool at_most_256_bins(const HbosParams& params, Eigen::Index n_features) {
  if (!params.features.empty() && static_cast<Eigen::Index>(params.features.size()) != n_features)
    return false;
  for (Eigen::Index j = 0; j < n_features; ++j) {
    const Binning& b = params.spec(j).binning;
    if (b.method != BinningMethod::EqualWidth || b.rule != BinCountRule::Fixed || b.bins < 1 ||
        b.shifts < 1 || b.bins > 256 / b.shifts)
      return false;
  }
  return true;
}

/// Reusable buffers of fit_and_score_columns (a Workspace keeps them, so frames do not allocate).
template <class Scalar, class BinIndex>
struct FitScoreBuffers {
  std::vector<Scalar> scratch;  // copies for sorting, wrapping, selecting
  std::vector<Scalar> storage;  // columns of expressions without direct access
  // n x d, column-major: the bin each value was counted in. Not zeroed on growth: an entry is
  // read only where its feature's fit wrote all of its column.
  std::vector<BinIndex, UninitializedAllocator<BinIndex>> bin_index;
  std::vector<unsigned char> recorded;  // per feature: whether its bin indices were recorded
  std::vector<Scalar> pair_table;       // contributions of features 0 and 1 summed, per bin pair
  std::vector<Scalar> range;            // 2 d: every feature's min, then every feature's max
};

/// fit_and_score_columns' histograms for data whose rows are contiguous runs (numpy's default C
/// order, a row-major matrix): a feature's column is strided there, and fitting feature by
/// feature would read the whole matrix twice per feature. Instead: every feature's range in one
/// sweep over the rows, then every feature counted per block of rows while the block is in
/// cache — the matrix is read twice in all, as a column-major one is. Bitwise the histograms
/// and bin indices of the per-feature fit (the staged fit places the same edges and counts the
/// same bins). Returns false, having done nothing that matters, when it does not apply: a
/// feature whose bins need more than its range (fits_from_range), a column-major layout, or a
/// non-finite value (the per-feature fit then names it).
template <class Scalar, class Derived, class BinIndex>
bool fit_rows_at_once(std::vector<Histogram<Scalar>>& histograms,
                      const Eigen::DenseBase<Derived>& x, const HbosParams& params,
                      FitScoreBuffers<Scalar, BinIndex>& buffers) {
  if constexpr ((Derived::Flags & Eigen::DirectAccessBit) == 0) {
    return false;
  } else {
    const Eigen::Index n = x.rows(), d = x.cols();
    const Derived& m = x.derived();
    if (d < 2 || m.colStride() != 1 || m.rowStride() < d) return false;
    for (Eigen::Index j = 0; j < d; ++j)
      if (!Histogram<Scalar>::fits_from_range(params.spec(j))) return false;
    const Scalar* data = m.data();
    const auto ud = static_cast<std::size_t>(d);
    buffers.range.resize(2 * ud);
    Scalar* lo = buffers.range.data();
    Scalar* hi = lo + d;
    if (!scan_rows_min_max(data, n, d, m.rowStride(), lo, hi)) return false;
    for (std::size_t j = 0; j < ud; ++j) {
      const auto feature = static_cast<Eigen::Index>(j);
      buffers.recorded[j] =
          histograms[j].template begin_staged_fit<BinIndex>(
              lo[j], hi[j], params.spec(feature), params.scoring, buffers.scratch, feature)
              ? 1
              : 0;
    }
    const auto un = static_cast<std::size_t>(n);
    detail::ByteBinConstants<Scalar> c0, c1;
    if (d == 2 && m.rowStride() == 2 && histograms[0].byte_bin_constants(c0) &&
        histograms[1].byte_bin_constants(c1)) {
      // Two features of contiguous rows, few bins each (the classic static job on numpy's
      // default layout): both features' bins come straight from the rows, with no gather of a
      // strided column, and are counted while they are in L1. A chunk is one round of
      // count_byte_indices (255 vectors of 16).
      constexpr std::size_t chunk = std::size_t{255} * 16;
      std::array<std::array<std::uint8_t, chunk>, 2> local{};  // bins not recorded as bytes
      for (std::size_t start = 0; start < un; start += chunk) {
        const std::size_t rows = std::min(chunk, un - start);
        std::array<std::uint8_t*, 2> b{local[0].data(), local[1].data()};
        if constexpr (std::is_same_v<BinIndex, std::uint8_t>) {
          for (std::size_t j = 0; j < 2; ++j)
            if (buffers.recorded[j] != 0) b[j] = buffers.bin_index.data() + j * un + start;
        }
        detail::interleaved_byte_bins_2(data + 2 * start, rows, c0, c1, b[0], b[1]);
        for (std::size_t j = 0; j < 2; ++j) {
          histograms[j].count_byte_bins(b[j], rows);
          if constexpr (!std::is_same_v<BinIndex, std::uint8_t>) {
            if (buffers.recorded[j] != 0)
              std::copy(b[j], b[j] + rows, buffers.bin_index.data() + j * un + start);
          }
        }
      }
      for (auto& h : histograms) h.end_staged_fit(n, params.scoring);
      return true;
    }
    // A block of rows small enough to stay in L2 while each feature takes its column of it;
    // the whole column at once when a feature has so many bins that clearing its interleaved
    // counters per block would cost more than the block.
    Eigen::Index most_bins = 0;
    for (const auto& h : histograms) most_bins = std::max(most_bins, h.bins());
    const Eigen::Index block =
        most_bins > 4096 ? n : std::max<Eigen::Index>(256, (Eigen::Index{1} << 16) / d);
    for (Eigen::Index start = 0; start < n; start += block) {
      const Eigen::Index rows = std::min(block, n - start);
      for (std::size_t j = 0; j < ud; ++j) {
        const ColumnView<Scalar> part{data + start * m.rowStride() + static_cast<Eigen::Index>(j),
                                      rows, m.rowStride()};
        BinIndex* index = buffers.recorded[j] != 0
                              ? buffers.bin_index.data() + j * un + static_cast<std::size_t>(start)
                              : nullptr;
        histograms[j].count_more(part, index);
      }
    }
    for (auto& h : histograms) h.end_staged_fit(n, params.scoring);
    return true;
  }
}

/// Fits `histograms` to `x` like fit_histograms and scores the training rows in the same sweep:
/// `scores` (n) and, when not null, `contributions` (column-major n x d). Where a histogram
/// records the bin each value was counted in (equal or fixed width, not periodic), the values are
/// scored straight from those indices, one table load each and no range checks; otherwise
/// through the general lookup. Either way the result is bitwise what scoring `x` with the fitted
/// histograms gives (a value is scored from the bin it was counted in, and the contributions are
/// added in feature order).
template <class Scalar, class Derived, class BinIndex>
void fit_and_score_columns(std::vector<Histogram<Scalar>>& histograms,
                           const Eigen::DenseBase<Derived>& x, const HbosParams& params,
                           FitScoreBuffers<Scalar, BinIndex>& buffers, Scalar* scores,
                           Scalar* contributions) {
  require(x.rows() > 0, "cannot fit to an empty data set (0 rows)");
  require(x.cols() > 0, "cannot fit to data with no features (0 columns)");
  validate(params, x.cols());
  const auto n = static_cast<std::size_t>(x.rows());
  const auto d = static_cast<std::size_t>(x.cols());
  histograms.resize(d);
  buffers.bin_index.resize(n * d);
  buffers.recorded.resize(d);
  const bool by_rows = fit_rows_at_once(histograms, x, params, buffers);
  for (std::size_t j = 0; j < d && !by_rows; ++j) {
    const auto feature = static_cast<Eigen::Index>(j);
    buffers.recorded[j] =
        histograms[j].refit(x.derived().col(feature), params.spec(feature), params.scoring,
                            buffers.scratch, feature, buffers.bin_index.data() + j * n)
            ? 1
            : 0;
  }
  // Column j's contributions into out[0, m) for rows [start, start + m): `accumulate` adds.
  auto contributions_of = [&](std::size_t j, std::size_t start, std::size_t m, Scalar* out,
                              bool accumulate) {
    const Histogram<Scalar>& h = histograms[j];
    const auto feature = static_cast<Eigen::Index>(j);
    if (buffers.recorded[j] != 0) {
      const Scalar* table = h.bin_contributions().data();
      const BinIndex* b = buffers.bin_index.data() + j * n + start;
      if (accumulate) {
        for (std::size_t i = 0; i < m; ++i) out[i] += table[b[i]];
      } else {
        for (std::size_t i = 0; i < m; ++i) out[i] = table[b[i]];
      }
      return;
    }
    ColumnView<Scalar> view = view_of(x.derived().col(feature), buffers.storage);
    view.data += static_cast<Eigen::Index>(start) * view.stride;
    view.size = static_cast<Eigen::Index>(m);
    h.contributions_into(view, out, accumulate, feature);
  };

  if (contributions != nullptr) {
    for (std::size_t j = 0; j < d; ++j) contributions_of(j, 0, n, contributions + j * n, false);
    std::copy(contributions, contributions + n, scores);
    for (std::size_t j = 1; j < d; ++j)
      for (std::size_t i = 0; i < n; ++i) scores[i] += contributions[j * n + i];
    return;
  }
  // Scores only: a block of rows at a time, every feature in turn, so the block's running sums
  // stay in L1 instead of streaming the whole score vector through memory once per feature.
  // Expressions without direct access are evaluated once per column instead (view_of would
  // re-evaluate them per block).
  constexpr bool direct = (Derived::Flags & Eigen::DirectAccessBit) != 0;
  const std::size_t block = direct ? 2048 : n;
  // The first two features, when both were scored by index and their bins are few: one load
  // from a table of t0[a] + t1[b] instead of two (the same Scalar sum, so the same bits).
  const std::size_t k0 = static_cast<std::size_t>(histograms[0].bins());
  const std::size_t k1 = d > 1 ? static_cast<std::size_t>(histograms[1].bins()) : 0;
  const bool paired =
      d > 1 && buffers.recorded[0] != 0 && buffers.recorded[1] != 0 && k0 * k1 <= 4096;
  if (paired) {
    const Scalar* t0 = histograms[0].bin_contributions().data();
    const Scalar* t1 = histograms[1].bin_contributions().data();
    buffers.pair_table.resize(k0 * k1);
    for (std::size_t a = 0; a < k0; ++a)
      for (std::size_t b = 0; b < k1; ++b) buffers.pair_table[a * k1 + b] = t0[a] + t1[b];
  }
  // Scores of the first two features are final when there are no others: for a large output
  // they are written past the caches (detail/byte_bins.hpp), saving the read of each line.
  const bool stream_scores = paired && d == 2 && n >= (std::size_t{1} << 20);
  for (std::size_t start = 0; start < n; start += block) {
    const std::size_t m = std::min(block, n - start);
    std::size_t j = 0;
    if (paired) {
      const Scalar* table = buffers.pair_table.data();
      const BinIndex* b0 = buffers.bin_index.data() + start;
      const BinIndex* b1 = b0 + n;
      Scalar* out = scores + start;
      if (k0 * k1 <= 256) {
        // The pair's index fits a byte: computed for the block in a loop the compiler
        // vectorises (or, for one-byte bins with AVX2, in registers), so the table loads are
        // all that is left per value.
        detail::lookup_byte_pairs(table, b0, b1, k1, m, out, stream_scores);
      } else {
        for (std::size_t i = 0; i < m; ++i)
          out[i] = table[static_cast<std::size_t>(b0[i]) * k1 + b1[i]];
      }
      j = 2;
    }
    for (; j < d; ++j) contributions_of(j, start, m, scores + start, j > 0);
  }
  if (stream_scores) detail::fence_streaming_stores();
}

}  // namespace detail

/// A fitted HBOS model. Create it with `Hbos<Scalar>::fit`; it cannot be modified afterwards.
template <class Scalar>
class Hbos {
  static_assert(std::is_floating_point_v<Scalar>, "Hbos needs float or double");

 public:
  using Index = Eigen::Index;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using RowMajorMap =
      Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;

  /// Fits one histogram per column of `x` (rows = samples).
  /// \throws InvalidArgument on empty input, non-finite values or invalid parameters.
  template <class Derived>
  [[nodiscard]] static Hbos fit(const Eigen::DenseBase<Derived>& x, const HbosParams& params = {}) {
    static_assert(std::is_same_v<typename Derived::Scalar, Scalar>,
                  "the data's scalar type must match the model's (Hbos<float> or Hbos<double>)");
    Hbos model;
    std::vector<Scalar> scratch;
    detail::fit_histograms(model.histograms_, x, params, scratch);
    for (auto& h : model.histograms_) h.release_fit_buffers();
    model.params_ = params;
    model.n_samples_ = x.rows();
    return model;
  }

  /// Fits like `fit` and writes the scores of the training rows into `training_scores`
  /// (x.rows() entries): exactly `model.score(x)`, as PyOD's `decision_scores_`, but each value
  /// is scored from the bin it was just counted in, so the lookup (range checks, bin arithmetic)
  /// is skipped — about half the cost of `fit` followed by `score` (docs/benchmarks.md).
  /// \throws InvalidArgument as `fit`, or when `training_scores` has the wrong size.
  template <class Derived>
  [[nodiscard]] static Hbos fit_and_score(const Eigen::DenseBase<Derived>& x,
                                          Eigen::Ref<Vector> training_scores,
                                          const HbosParams& params = {}) {
    static_assert(std::is_same_v<typename Derived::Scalar, Scalar>,
                  "the data's scalar type must match the model's (Hbos<float> or Hbos<double>)");
    detail::require(training_scores.size() == x.rows(), "training score output has ",
                    training_scores.size(), " entries for ", x.rows(), " rows");
    Hbos model;
    // Bin indices in one byte when every feature is known to have at most 256 bins (the default
    // and classic static specs: half the index traffic), else in 16 bits (the default
    // max_bins, 65536); a histogram with more bins than its index type holds takes the lookup.
    if (detail::at_most_256_bins(params, x.cols())) {
      detail::FitScoreBuffers<Scalar, std::uint8_t> buffers;
      detail::fit_and_score_columns(model.histograms_, x, params, buffers, training_scores.data(),
                                    static_cast<Scalar*>(nullptr));
    } else {
      detail::FitScoreBuffers<Scalar, std::uint16_t> buffers;
      detail::fit_and_score_columns(model.histograms_, x, params, buffers, training_scores.data(),
                                    static_cast<Scalar*>(nullptr));
    }
    for (auto& h : model.histograms_) h.release_fit_buffers();
    model.params_ = params;
    model.n_samples_ = x.rows();
    return model;
  }

  /// Fits to a raw row-major buffer of `rows` x `cols` values (read in place).
  [[nodiscard]] static Hbos fit_row_major(const Scalar* data, Index rows, Index cols,
                                          const HbosParams& params = {}) {
    check_shape(data, rows, cols);
    return fit(RowMajorMap(data, rows, cols), params);
  }

  /// Scores every row of `x` (n x d, d = n_features()).
  template <class Derived>
  [[nodiscard]] Vector score(const Eigen::DenseBase<Derived>& x) const {
    check_input(x);
    Vector out(x.rows());
    std::vector<Scalar> storage;
    detail::write_scores(histograms_, x, out.data(), static_cast<Scalar*>(nullptr), storage);
    return out;
  }

  /// Scores a raw row-major buffer.
  [[nodiscard]] Vector score_row_major(const Scalar* data, Index rows, Index cols) const {
    check_shape(data, rows, cols);
    return score(RowMajorMap(data, rows, cols));
  }

  /// Scores into a caller-provided vector of x.rows() entries (no allocation).
  template <class Derived>
  void score_into(const Eigen::DenseBase<Derived>& x, Eigen::Ref<Vector> out) const {
    check_input(x);
    detail::require(out.size() == x.rows(), "score output has ", out.size(), " entries for ",
                    x.rows(), " rows");
    std::vector<Scalar> storage;  // used only by expressions without direct access
    detail::write_scores(histograms_, x, out.data(), static_cast<Scalar*>(nullptr), storage);
  }

  /// Per-feature contributions, n x d; each row sums to that row's score.
  template <class Derived>
  [[nodiscard]] Matrix contributions(const Eigen::DenseBase<Derived>& x) const {
    check_input(x);
    Matrix out(x.rows(), x.cols());
    Vector scores(x.rows());
    std::vector<Scalar> storage;
    detail::write_scores(histograms_, x, scores.data(), out.data(), storage);
    return out;
  }

  [[nodiscard]] Index n_features() const { return static_cast<Index>(histograms_.size()); }
  /// Number of training samples.
  [[nodiscard]] Index n_samples() const { return n_samples_; }
  [[nodiscard]] const Histogram<Scalar>& histogram(Index j) const {
    detail::require(j >= 0 && j < n_features(), "feature index ", j, " out of range [0, ",
                    n_features(), ")");
    return histograms_[static_cast<std::size_t>(j)];
  }
  [[nodiscard]] const HbosParams& params() const { return params_; }

  /// Assembles a model from fitted histograms, one per feature (model files, merged fits: see
  /// hbos/model_file.hpp, hbos/merge.hpp). Each histogram must agree with the spec `params`
  /// gives its feature (periodic, tail, shifts, uniform bins) and count `n_samples` samples.
  /// \throws InvalidArgument naming the first feature that does not.
  [[nodiscard]] static Hbos from_histograms(std::vector<Histogram<Scalar>> histograms,
                                            const HbosParams& params, Index n_samples) {
    const auto d = static_cast<Index>(histograms.size());
    detail::require(d > 0, "a model needs at least one feature histogram");
    detail::validate(params, d);
    for (Index j = 0; j < d; ++j)
      detail::check_against_spec(histograms[static_cast<std::size_t>(j)].parts(), params.spec(j),
                                 n_samples, j);
    Hbos model;
    model.histograms_ = std::move(histograms);
    model.params_ = params;
    model.n_samples_ = n_samples;
    return model;
  }

 private:
  Hbos() = default;

  static void check_shape(const Scalar* data, Index rows, Index cols) {
    detail::require(rows >= 0 && cols >= 0, "row-major buffer shape must be non-negative, got ",
                    rows, " x ", cols);
    detail::require(data != nullptr || rows == 0 || cols == 0, "row-major buffer is null");
  }

  template <class Derived>
  void check_input(const Eigen::DenseBase<Derived>& x) const {
    static_assert(std::is_same_v<typename Derived::Scalar, Scalar>,
                  "the data's scalar type must match the model's (Hbos<float> or Hbos<double>)");
    detail::require(x.cols() == n_features(), "the model was fitted on ", n_features(),
                    " features but the data to score has ", x.cols(), " columns");
  }

  std::vector<Histogram<Scalar>> histograms_;
  HbosParams params_;
  Index n_samples_ = 0;
};

using Hbosd = Hbos<double>;
using Hbosf = Hbos<float>;

}  // namespace hbos
