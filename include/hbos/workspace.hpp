#pragma once
/// \file
/// The SLAM hot path: fit, score and threshold one frame's data with no heap allocation after
/// warm-up.
///
/// A tracker screens a few hundred to a few thousand matches per frame, each with a couple of
/// features. Building a fresh `Hbos` every frame would allocate its histograms and outputs each
/// time; a `Workspace` keeps them and reuses their capacity. Once it has seen a frame at least as
/// large as the current one (or after `reserve`), `run` performs no heap allocation at all —
/// tests/unit/test_workspace.cpp proves it with a counting allocator.
///
///     hbos::Workspace<float> ws(params, hbos::AdaptiveRange{0.7});
///     for (each frame) {
///       const auto summary = ws.run(features);          // n x d, rows = matches
///       use(ws.inlier(), ws.scores(), summary.threshold);
///     }
///
/// Threading: a Workspace is single-threaded state; use one per thread.

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <memory>
#include <utility>
#include <variant>
#include <vector>

#include "hbos/histogram.hpp"
#include "hbos/model.hpp"
#include "hbos/threshold.hpp"

namespace hbos {

/// What one `Workspace::run` decided.
template <class Scalar>
struct FrameSummary {
  Scalar threshold{};       ///< outliers have score > threshold
  Eigen::Index n_rows = 0;  ///< samples screened
  Eigen::Index n_inliers = 0;
  [[nodiscard]] Eigen::Index n_outliers() const { return n_rows - n_inliers; }
};

/// Reusable per-frame fit + score + threshold. See the file comment.
template <class Scalar>
class Workspace {
 public:
  using Index = Eigen::Index;
  using VectorMap = Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>;
  using MatrixMap = Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>>;
  using MaskMap = Eigen::Map<const Eigen::Array<bool, Eigen::Dynamic, 1>>;

  explicit Workspace(HbosParams params = {}, ThresholdRule rule = AdaptiveRange{})
      : params_(std::move(params)), rule_(rule) {
    std::visit([](const auto& r) { detail::validate(r); }, rule_);
  }

  /// Grows every buffer for frames up to `rows` x `cols` and `bins` bins per feature, so that
  /// even the first `run` of that size does not allocate.
  void reserve(Index rows, Index cols, Index bins = 1024) {
    detail::require(rows >= 0 && cols >= 0, "Workspace::reserve: rows and cols must be >= 0, got ",
                    rows, " x ", cols);
    const auto n = static_cast<std::size_t>(rows);
    const auto d = static_cast<std::size_t>(cols);
    contributions_.reserve(n * d);
    scores_.reserve(n);
    grow_mask(n);
    buffers_.scratch.reserve(n);
    buffers_.storage.reserve(n);
    buffers_.bin_index.reserve(n * d);
    buffers_.recorded.reserve(d);
    threshold_scratch_.reserve(n);
    histograms_.resize(std::max(histograms_.size(), d));
    for (auto& h : histograms_) h.reserve(bins);
  }

  /// Fits a histogram per column of `x`, scores every row and applies the threshold rule.
  /// Results stay valid until the next call (scores(), contributions(), inlier(), histogram()).
  /// \throws InvalidArgument on empty or non-finite input.
  template <class Derived>
  FrameSummary<Scalar> run(const Eigen::DenseBase<Derived>& x) {
    static_assert(std::is_same_v<typename Derived::Scalar, Scalar>,
                  "the data's scalar type must match the workspace's");
    detail::require(x.rows() > 0, "cannot fit to an empty data set (0 rows)");
    detail::require(x.cols() > 0, "cannot fit to data with no features (0 columns)");
    detail::validate(params_, x.cols());
    rows_ = x.rows();
    cols_ = x.cols();
    const auto n = static_cast<std::size_t>(rows_);
    contributions_.resize(n * static_cast<std::size_t>(cols_));
    scores_.resize(n);
    grow_mask(n);
    detail::fit_and_score_columns(histograms_, x, params_, buffers_, scores_.data(),
                                  contributions_.data());
    const Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>> scores(scores_.data(), rows_);

    FrameSummary<Scalar> summary;
    summary.n_rows = rows_;
    summary.threshold = compute_threshold(scores, rule_, threshold_scratch_);
    Eigen::Map<Eigen::Array<bool, Eigen::Dynamic, 1>> inlier(inlier_.get(), rows_);
    summary.n_inliers = apply_threshold(scores, summary.threshold, inlier);
    return summary;
  }

  /// Scores of the last run (one per row).
  [[nodiscard]] VectorMap scores() const { return VectorMap(scores_.data(), rows_); }
  /// Per-feature contributions of the last run (rows x features); rows sum to scores().
  [[nodiscard]] MatrixMap contributions() const {
    return MatrixMap(contributions_.data(), rows_, cols_);
  }
  /// inlier()[i] == (scores()[i] <= threshold) for the last run.
  [[nodiscard]] MaskMap inlier() const { return MaskMap(inlier_.get(), rows_); }
  /// The histogram of feature j fitted by the last run.
  [[nodiscard]] const Histogram<Scalar>& histogram(Index j) const {
    detail::require(j >= 0 && j < cols_, "feature index ", j, " out of range [0, ", cols_, ")");
    return histograms_[static_cast<std::size_t>(j)];
  }
  [[nodiscard]] const HbosParams& params() const { return params_; }
  [[nodiscard]] const ThresholdRule& rule() const { return rule_; }

 private:
  void grow_mask(std::size_t n) {
    if (n <= inlier_capacity_) return;
    inlier_ = std::make_unique<bool[]>(n);
    inlier_capacity_ = n;
  }

  HbosParams params_;
  ThresholdRule rule_;
  std::vector<Histogram<Scalar>> histograms_;
  std::vector<Scalar> threshold_scratch_, scores_, contributions_;
  detail::FitScoreBuffers<Scalar, std::uint16_t> buffers_;  // fitting and index scoring
  // Not std::vector<bool>: the mask must be addressable as bool[] for the Eigen map.
  std::unique_ptr<bool[]> inlier_;
  std::size_t inlier_capacity_ = 0;
  Index rows_ = 0, cols_ = 0;
};

}  // namespace hbos
