#pragma once
/// \file
/// The reprojection screen: turns one frame's matches into scores, a threshold and an inlier
/// mask, with any strategy of screen_strategies.hpp, and the iterated screen -> refit -> re-screen
/// mode that ORB-SLAM2's four optimisation rounds follow.
///
/// The HBOS strategy, per frame (n matches, F = the fit set: unflagged matches unless fewer than
/// `min_fit_matches`, or all):
///  1. r_i = observed_i - predicted_i [px]; c(p) = the dominant residual field of F
///     (residuals.hpp: constant or affine in the predicted pixel p), or 0.
///  2. m_i = |r_i - c(p_i)| / sigma_i (or unwhitened), clipped at `magnitude_clip`;
///     a_i = atan2 of r_i - c(p_i) when an angle feature is used.
///  3. One histogram per feature fitted on F (histogram.hpp): contribution
///     c_j(v) = log(h_max / h(bin of v)) (Goldstein & Dengel, eq. 1); Upper tail for m.
///  4. score_i = sum_j c_j (the paper's eq. 5 with natural logs).
///  5. threshold t from the rule on the scores of F (the paper's eq. 6 for `paper()`).
///  6. inlier_i = score_i <= t, or m_i <= keep_below (noise floor); flagged matches are rejected
///     under FlaggedPolicy::Reject.
///
/// Baselines reuse steps 1 and 5-6 with their own statistic as the score.
///
/// Threading: a ReprojectionScreen is a workspace: not thread-safe; use one per thread. Its
/// result is valid until the next call. After a warm-up call with the largest frame (n matches,
/// and for HBOS the largest bin count, bounded through `magnitude_clip`), calls allocate nothing.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "hbos/error.hpp"
#include "hbos/histogram.hpp"
#include "hbos/screening/residual_field.hpp"
#include "hbos/screening/strategies.hpp"
#include "hbos/threshold.hpp"

namespace hbos {

template <class Scalar>
class ReprojectionScreen;

/// The outcome of screening one frame. Owned by the ReprojectionScreen that produced it.
template <class Scalar>
class ScreenResult {
 public:
  using Index = Eigen::Index;
  using ArrayMap = Eigen::Map<const Eigen::Array<Scalar, Eigen::Dynamic, 1>>;
  using MatrixMap = Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>>;
  using MaskMap = Eigen::Map<const Eigen::Array<std::uint8_t, Eigen::Dynamic, 1>>;

  /// Number of matches screened.
  [[nodiscard]] Index size() const { return n_; }
  /// Per-match score, higher = more likely an outlier (the strategy's decision statistic).
  [[nodiscard]] ArrayMap scores() const { return ArrayMap(score_.data(), n_); }
  [[nodiscard]] Scalar score(Index i) const { return score_[static_cast<std::size_t>(i)]; }
  /// The cut: a match is an outlier when its score is above it (unless kept by the noise floor).
  [[nodiscard]] Scalar threshold() const { return threshold_; }
  /// inlier(i) is 1 for a kept match, 0 for a rejected one.
  [[nodiscard]] MaskMap inliers() const { return MaskMap(inlier_.data(), n_); }
  [[nodiscard]] bool inlier(Index i) const { return inlier_[static_cast<std::size_t>(i)] != 0; }
  /// The residual feature the decision was made on: the (centered, whitened) magnitude for HBOS,
  /// MAD and whitened quantile gates, |r| [px] for the fixed and quantile gates, |r|/sigma for
  /// chi^2.
  [[nodiscard]] Scalar magnitude(Index i) const { return magnitude_[static_cast<std::size_t>(i)]; }
  /// Per-feature contributions, n x n_features(); rows sum to the scores (HBOS), or the one
  /// column is the score itself (baselines).
  [[nodiscard]] MatrixMap contributions() const {
    return MatrixMap(contribution_.data(), n_, n_features_);
  }
  [[nodiscard]] Index n_features() const { return n_features_; }
  /// "magnitude", "angle", or the baseline's statistic name, for feature j.
  [[nodiscard]] const char* feature_name(Index j) const {
    return feature_names_[static_cast<std::size_t>(j)];
  }
  [[nodiscard]] Index n_inliers() const { return n_inliers_; }
  [[nodiscard]] Index n_outliers() const { return n_ - n_inliers_; }
  /// Matches flagged on a dynamic mask, and how many of them were rejected.
  [[nodiscard]] Index n_flagged() const { return n_flagged_; }
  [[nodiscard]] Index n_flagged_rejected() const { return n_flagged_rejected_; }
  /// Matches kept only by the noise floor (score above the threshold, magnitude below keep_below).
  [[nodiscard]] Index n_kept_by_noise_floor() const { return n_floor_; }
  /// Matches the histograms, centers and quantiles were fitted on.
  [[nodiscard]] Index n_fitted() const { return n_fitted_; }
  /// The dominant residual field subtracted before the magnitude (zero when not centering).
  [[nodiscard]] const ResidualField<Scalar>& field() const { return field_; }
  /// Screening rounds run (1 for a single screen; see ReprojectionScreen::screen_iterated).
  [[nodiscard]] int rounds() const { return rounds_; }

 private:
  friend class ReprojectionScreen<Scalar>;
  Index n_ = 0;
  Index n_features_ = 0;
  std::vector<Scalar> score_, magnitude_, contribution_;
  std::vector<std::uint8_t> inlier_;
  const char* feature_names_[2] = {"", ""};
  Scalar threshold_ = 0;
  Index n_inliers_ = 0, n_flagged_ = 0, n_flagged_rejected_ = 0, n_floor_ = 0, n_fitted_ = 0;
  ResidualField<Scalar> field_{};
  int rounds_ = 0;
};

/// Screens reprojection matches. Construct once with a config, call `screen` per frame.
/// See the file comment for the algorithm and the threading note.
template <class Scalar>
class ReprojectionScreen {
  static_assert(std::is_floating_point_v<Scalar>, "ReprojectionScreen needs float or double");

 public:
  using Index = Eigen::Index;

  /// \throws InvalidArgument if the config is invalid.
  explicit ReprojectionScreen(const ScreenConfig& config = {}) : config_(config) {
    detail::validate(config_);
  }
  /// Convenience: a strategy with the default screen-wide settings.
  explicit ReprojectionScreen(const ScreenStrategy& strategy)
      : ReprojectionScreen(ScreenConfig{strategy}) {}

  [[nodiscard]] const ScreenConfig& config() const { return config_; }
  /// Replaces the config (validated); buffers are kept.
  void set_config(const ScreenConfig& config) {
    detail::validate(config);
    config_ = config;
  }

  /// Screens one frame. The result stays valid until the next call on this object.
  /// \throws InvalidArgument when there are no matches.
  const ScreenResult<Scalar>& screen(const Matches<Scalar>& matches) {
    run(matches);
    result_.rounds_ = 1;
    return result_;
  }

  /// Screen -> refit -> re-screen, `rounds` screenings in all (ORB-SLAM2 runs 4). After each
  /// screening but the last, `refit(result, matches)` re-estimates the pose from the inliers and
  /// writes the new predictions into `matches` (Matches::set_predicted); it returns false to stop
  /// early (e.g. too few inliers). Every round screens *all* matches again, so a match rejected
  /// under the rough pose can come back, as in ORB-SLAM2.
  template <class Refit>
  const ScreenResult<Scalar>& screen_iterated(Matches<Scalar>& matches, Refit&& refit, int rounds) {
    detail::require(rounds >= 1, "screen_iterated needs rounds >= 1, got ", rounds);
    int done = 0;
    for (int r = 0; r < rounds; ++r) {
      run(matches);
      ++done;
      if (r + 1 == rounds) break;
      if (!refit(static_cast<const ScreenResult<Scalar>&>(result_), matches)) break;
    }
    result_.rounds_ = done;
    return result_;
  }

  /// The last result.
  [[nodiscard]] const ScreenResult<Scalar>& result() const { return result_; }

  /// Grows every buffer for frames of up to `n` matches, and the magnitude histogram to the most
  /// bins its config can produce (FixedWidth: magnitude_clip / width), so that not even the first
  /// frame of that size allocates.
  void reserve(Index n) {
    detail::require(n >= 1, "reserve needs n >= 1, got ", n);
    const auto k = static_cast<std::size_t>(n);
    for (auto* v : {&result_.score_, &result_.magnitude_, &angle_, &fit_values_, &scratch_})
      v->reserve(k);
    result_.contribution_.reserve(2 * k);
    result_.inlier_.reserve(k);
    angle_used_.reserve(k);
    samples_.reserve(k);
    if (const auto* s = std::get_if<HbosScreen>(&config_.strategy)) {
      // Fitting the extremes [0, clip] makes the histogram take its largest bin count once.
      const Scalar top =
          s->magnitude_clip > 0.0 ? static_cast<Scalar>(s->magnitude_clip) : Scalar(1);
      fit_values_.assign({Scalar(0), top});
      magnitude_hist_.refit(
          Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>(fit_values_.data(), 2),
          s->magnitude, s->scoring, scratch_, 0);
      if (s->angle != AngleFeature::None) {
        fit_values_.assign({Scalar(-3.14159265358979), Scalar(3.14159265358979)});
        angle_hist_.refit(
            Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>(fit_values_.data(), 2),
            s->angle_spec, s->scoring, scratch_, 1);
      }
    }
  }

 private:
  void run(const Matches<Scalar>& matches);
  void prepare(const Matches<Scalar>& matches, Index n_features);
  void run_hbos(const Matches<Scalar>& matches, const HbosScreen& s);
  void run_gate(const Matches<Scalar>& matches);
  void finish(const Matches<Scalar>& matches, Scalar floor);
  [[nodiscard]] bool in_fit(const Matches<Scalar>& matches, Index i) const {
    return !fit_unflagged_only_ || !matches.on_dynamic_mask(i);
  }
  /// Copies the values of the fit set into fit_values_ and returns them as an Eigen column.
  Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>> fit_column(
      const Matches<Scalar>& matches, const std::vector<Scalar>& values) {
    Index m = 0;
    for (Index i = 0; i < matches.size(); ++i)
      if (in_fit(matches, i))
        fit_values_[static_cast<std::size_t>(m++)] = values[static_cast<std::size_t>(i)];
    return Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>(fit_values_.data(), m);
  }

  ScreenConfig config_;
  ScreenResult<Scalar> result_;
  Histogram<Scalar> magnitude_hist_, angle_hist_;
  std::vector<Scalar> angle_, fit_values_, scratch_;
  std::vector<std::uint8_t> angle_used_;
  detail::FieldSamples<Scalar> samples_;
  bool fit_unflagged_only_ = false;
};

using ReprojectionScreend = ReprojectionScreen<double>;
using ReprojectionScreenf = ReprojectionScreen<float>;

// ---------------------------------------------------------------------------------------------
// Implementation
// ---------------------------------------------------------------------------------------------

template <class Scalar>
void ReprojectionScreen<Scalar>::prepare(const Matches<Scalar>& matches, Index n_features) {
  const Index n = matches.size();
  detail::require(n > 0, "cannot screen an empty set of matches");
  const auto k = static_cast<std::size_t>(n);
  ScreenResult<Scalar>& r = result_;
  r.n_ = n;
  r.n_features_ = n_features;
  r.score_.resize(k);
  r.magnitude_.resize(k);
  r.inlier_.resize(k);
  r.contribution_.resize(k * static_cast<std::size_t>(n_features));
  fit_values_.resize(k);
  r.field_ = ResidualField<Scalar>{};

  Index flagged = 0;
  for (Index i = 0; i < n; ++i) flagged += matches.on_dynamic_mask(i) ? 1 : 0;
  r.n_flagged_ = flagged;
  fit_unflagged_only_ = config_.flagged != FlaggedPolicy::Ignore && flagged > 0 &&
                        n - flagged >= config_.min_fit_matches;
  r.n_fitted_ = fit_unflagged_only_ ? n - flagged : n;
}

template <class Scalar>
void ReprojectionScreen<Scalar>::run(const Matches<Scalar>& matches) {
  if (const auto* s = std::get_if<HbosScreen>(&config_.strategy)) {
    run_hbos(matches, *s);
  } else {
    run_gate(matches);
  }
}

template <class Scalar>
void ReprojectionScreen<Scalar>::run_hbos(const Matches<Scalar>& matches, const HbosScreen& s) {
  const Index n_features = s.angle == AngleFeature::None ? 1 : 2;
  prepare(matches, n_features);
  ScreenResult<Scalar>& r = result_;
  const Index n = matches.size();
  const auto un = static_cast<std::size_t>(n);
  r.feature_names_[0] = "magnitude";
  r.feature_names_[1] = "angle";

  // 1-2. Center, magnitude (clipped), angle.
  if (s.residuals.center != ResidualCenter::None) {
    detail::collect_field_samples(
        matches, [&](Index i) { return in_fit(matches, i); }, samples_);
    r.field_ = detail::dominant_field(samples_, s.residuals.center, s.residuals.center_window,
                                      s.residuals.center_iterations, scratch_);
  }
  const auto clip = static_cast<Scalar>(s.magnitude_clip);
  angle_.resize(un);
  for (Index i = 0; i < n; ++i) {
    const Eigen::Matrix<Scalar, 2, 1> c = r.field_.at(matches.predicted(i));
    const Eigen::Matrix<Scalar, 2, 1> d = matches.residual(i) - c;
    // A stereo component shifts with the pose error like u does: center it by c_x.
    const Scalar right = matches.has_right(i) ? matches.right_residual(i) - c.x() : Scalar(0);
    Scalar m = std::sqrt(d.squaredNorm() + right * right);
    if (s.residuals.whiten) m /= matches.sigma(i);
    if (clip > Scalar(0)) m = std::min(m, clip);
    r.magnitude_[static_cast<std::size_t>(i)] = m;
    if (s.angle != AngleFeature::None)
      angle_[static_cast<std::size_t>(i)] = std::atan2(d.y(), d.x());
  }

  // 3. Histograms fitted on the fit set; contributions for every match.
  magnitude_hist_.refit(fit_column(matches, r.magnitude_), s.magnitude, s.scoring, scratch_, 0);
  Scalar* c_mag = r.contribution_.data();
  for (Index i = 0; i < n; ++i)
    c_mag[i] = magnitude_hist_.contribution(r.magnitude_[static_cast<std::size_t>(i)]);
  if (s.angle != AngleFeature::None) {
    Scalar* c_ang = r.contribution_.data() + n;
    // AboveNoise: only residuals clearly above the noise have a meaningful direction; they alone
    // build the angle histogram and pay for it.
    const bool gated = s.angle == AngleFeature::AboveNoise;
    const auto gate = static_cast<Scalar>(s.angle_gate);
    angle_used_.resize(un);
    Index m = 0;
    for (Index i = 0; i < n; ++i) {
      const bool used = !gated || r.magnitude_[static_cast<std::size_t>(i)] > gate;
      angle_used_[static_cast<std::size_t>(i)] = used ? 1 : 0;
      if (used && in_fit(matches, i))
        fit_values_[static_cast<std::size_t>(m++)] = angle_[static_cast<std::size_t>(i)];
    }
    if (m > 0) {
      angle_hist_.refit(
          Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>(fit_values_.data(), m),
          s.angle_spec, s.scoring, scratch_, 1);
    }
    for (Index i = 0; i < n; ++i) {
      c_ang[i] = (m > 0 && angle_used_[static_cast<std::size_t>(i)])
                     ? angle_hist_.contribution(angle_[static_cast<std::size_t>(i)])
                     : Scalar(0);
    }
  }

  // 4. Scores.
  for (Index i = 0; i < n; ++i) {
    Scalar sum = 0;
    for (Index j = 0; j < n_features; ++j)
      sum += r.contribution_[static_cast<std::size_t>(j * n + i)];
    r.score_[static_cast<std::size_t>(i)] = sum;
  }

  // 5. Threshold on the fit set's scores.
  r.threshold_ = compute_threshold(fit_column(matches, r.score_), s.threshold, scratch_);
  finish(matches, static_cast<Scalar>(s.keep_below));
}

template <class Scalar>
void ReprojectionScreen<Scalar>::run_gate(const Matches<Scalar>& matches) {
  prepare(matches, 1);
  ScreenResult<Scalar>& r = result_;
  const Index n = matches.size();
  struct Statistic {
    bool whiten;
    bool squared;
    const char* name;
  };
  const ScreenStrategy& strategy = config_.strategy;
  Statistic stat{false, false, "residual_px"};
  if (std::holds_alternative<ChiSquareGate>(strategy)) stat = {true, true, "chi2"};
  if (const auto* q = std::get_if<QuantileGate>(&strategy)) stat.whiten = q->whiten;
  if (const auto* g = std::get_if<MadGate>(&strategy)) stat.whiten = g->whiten;
  if (stat.whiten && !stat.squared) stat.name = "residual_whitened";
  r.feature_names_[0] = stat.name;

  const auto* chi = std::get_if<ChiSquareGate>(&strategy);
  for (Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Scalar e2 = matches.squared_residual(i);
    const Scalar s2 = matches.sigma(i) * matches.sigma(i);
    const Scalar m = stat.whiten ? std::sqrt(e2 / s2) : std::sqrt(e2);
    r.magnitude_[k] = m;
    Scalar score = m;
    if (chi != nullptr) {
      // One threshold for mixed frames: a stereo match's chi^2 is rescaled to the 2-dof gate.
      score = e2 / s2;
      if (matches.has_right(i)) score *= static_cast<Scalar>(chi->chi2_mono / chi->chi2_stereo);
    }
    r.score_[k] = score;
    r.contribution_[k] = score;
  }

  if (const auto* g = std::get_if<FixedPixelGate>(&strategy)) {
    r.threshold_ = static_cast<Scalar>(g->max_px);
  } else if (chi != nullptr) {
    r.threshold_ = static_cast<Scalar>(chi->chi2_mono);
  } else if (const auto* q = std::get_if<QuantileGate>(&strategy)) {
    const auto column = fit_column(matches, r.score_);
    scratch_.resize(static_cast<std::size_t>(column.size()));
    std::copy(column.data(), column.data() + column.size(), scratch_.begin());
    r.threshold_ = detail::numpy_percentile_linear(scratch_.data(), scratch_.data() + column.size(),
                                                   q->quantile);
  } else {
    const auto& mad = std::get<MadGate>(strategy);
    r.threshold_ =
        compute_threshold(fit_column(matches, r.score_), MedianMad{mad.k, true}, scratch_);
  }
  finish(matches, Scalar(0));
}

template <class Scalar>
void ReprojectionScreen<Scalar>::finish(const Matches<Scalar>& matches, Scalar floor) {
  ScreenResult<Scalar>& r = result_;
  const bool reject_flagged = config_.flagged == FlaggedPolicy::Reject;
  Index kept = 0, floor_kept = 0, flagged_rejected = 0;
  for (Index i = 0; i < matches.size(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    const bool below = r.score_[k] <= r.threshold_;
    const bool floored = !below && r.magnitude_[k] <= floor;
    bool keep = below || floored;
    if (reject_flagged && matches.on_dynamic_mask(i)) keep = false;
    if (keep && floored) ++floor_kept;
    if (!keep && matches.on_dynamic_mask(i)) ++flagged_rejected;
    r.inlier_[k] = keep ? 1 : 0;
    kept += keep ? 1 : 0;
  }
  r.n_inliers_ = kept;
  r.n_floor_ = floor_kept;
  r.n_flagged_rejected_ = flagged_rejected;
}

}  // namespace hbos
