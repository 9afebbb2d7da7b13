#pragma once
/// \file
/// The reprojection screen: turns one frame's matches into scores, a cut and an inlier mask,
/// with any strategy of strategies.hpp. One call is one round; the rounds of ORB-SLAM2's pose
/// optimisation (screen -> refine -> re-project -> re-screen) belong to the caller, as
/// PoseOptimization owns its loop (projection.hpp has a small helper that writes it).
///
/// The HBOS strategy, per frame (n matches, F = the fit set: unflagged matches unless fewer than
/// `min_fit_matches`, or all):
///  1. r_i = observed_i - predicted_i [px]; c(p) = the dominant residual field of F
///     (residual_field.hpp: constant or affine in the predicted pixel p), with crowded image
///     cells capped (FieldFit), or 0.
///  2. d_i = (r_i - c(p_i)) / sigma_i, m_i = |d_i| (or unwhitened), clipped at `magnitude_clip`.
///  With the noise gate (the default):
///  3. s = the robust noise scale of m over F (noise_scale.hpp), at least the detector's own
///     (NoiseGate::min_scale), G = max(floor, scales s).
///  4. Evidence per match: coherence l_i (neighbourhood.hpp; its consensus is over the fit set's
///     neighbours inside the gate, and with CoherenceEvidence::flagged_consensus a flagged
///     match's over the flagged ones too), mask neighbourhood, history; each fires above its
///     floor (mask and history only where m_i is above their `min_scales` s).
///  5. B = the matches of F that look static (m <= G, no evidence fired); with
///     FieldFit::refit_on_static the field is refitted on B and steps 2-5 run once more.
///  6. One histogram per evidence feature (and the magnitude) fitted on B (histogram.hpp,
///     Upper tail): contribution c_j(v) = log(h_max / h(bin of v)) (Goldstein & Dengel, eq. 1).
///     E_i = the sum over the features that fired (the magnitude's counts only with another).
///  7. reject when m_i > G or E_i > t; score_i = max(t m_i / G, E_i), cut t.
///  Without it (magnitude_only(), paper()):
///  3. one histogram per feature (magnitude, optionally angle) fitted on F; score = the sum;
///     cut from the threshold rule on F's scores (the paper's eq. 6 for `paper()`).
///  Flagged matches are rejected under FlaggedPolicy::Reject.
///
/// Baselines reuse step 1's residuals with their own statistic as the score.
///
/// Threading: a ReprojectionScreen is a workspace: not thread-safe; use one per thread. Its
/// result is valid until the next call. After a warm-up call with the largest frame (n matches,
/// and for HBOS the largest bin count, bounded through `magnitude_clip`), calls allocate nothing.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "hbos/error.hpp"
#include "hbos/histogram.hpp"
#include "hbos/screening/matches.hpp"
#include "hbos/screening/neighbourhood.hpp"
#include "hbos/screening/noise_scale.hpp"
#include "hbos/screening/residual_field.hpp"
#include "hbos/screening/rigid_field.hpp"
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
  /// The unit of scores and threshold: "score" (HBOS: a sum of log density ratios), "px",
  /// "px/sigma", or "px^2/sigma^2" (chi^2).
  [[nodiscard]] const char* unit() const { return unit_; }
  /// The cut in the magnitude's units (magnitude_unit()) where the decision is a gate on the
  /// magnitude: the noise gate G of HBOS, the gates' own cut (sqrt for chi^2); NaN otherwise.
  [[nodiscard]] Scalar magnitude_cut() const { return magnitude_cut_; }
  /// "px" or "px/sigma".
  [[nodiscard]] const char* magnitude_unit() const { return magnitude_unit_; }
  /// The frame's robust noise scale s [px/sigma], at least NoiseGate::min_scale (HBOS with the
  /// noise gate); NaN otherwise.
  [[nodiscard]] Scalar noise_scale() const { return noise_scale_; }
  /// The coherence evidence l_i of match i (log-likelihood ratio, CoherenceEvidence); 0 when
  /// not computed.
  [[nodiscard]] Scalar coherence(Index i) const {
    return coherence_.empty() ? Scalar(0) : coherence_[static_cast<std::size_t>(i)];
  }
  /// Matches inside the noise gate rejected on their evidence (HBOS with the noise gate).
  [[nodiscard]] Index n_rejected_by_evidence() const { return n_evidence_; }
  /// inlier(i) is 1 for a kept match, 0 for a rejected one.
  [[nodiscard]] MaskMap inliers() const { return MaskMap(inlier_.data(), n_); }
  [[nodiscard]] bool inlier(Index i) const { return inlier_[static_cast<std::size_t>(i)] != 0; }
  /// The residual feature the decision was made on: the (centered, whitened) magnitude for HBOS,
  /// MAD and whitened quantile gates, |r| [px] for the fixed and quantile gates, |r|/sigma for
  /// chi^2.
  [[nodiscard]] Scalar magnitude(Index i) const {
    const auto k = static_cast<std::size_t>(i);
    switch (magnitude_source_) {
      case MagnitudeSource::Score:
        return score_[k];
      case MagnitudeSource::SqrtScore:
        return std::sqrt(score_[k]);
      case MagnitudeSource::Stored:
        break;
    }
    return magnitude_[k];
  }
  /// Per-feature contributions, n x n_features(); rows sum to the scores (HBOS), or the one
  /// column is the score itself (baselines).
  [[nodiscard]] MatrixMap contributions() const {
    return MatrixMap(
        n_features_ == 1 && contribution_is_score_ ? score_.data() : contribution_.data(), n_,
        n_features_);
  }
  [[nodiscard]] Index n_features() const { return n_features_; }
  /// "magnitude", "angle", "coherence", "mask", "history", or the baseline's statistic name.
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

 private:
  friend class ReprojectionScreen<Scalar>;
  // The gates derive the magnitude and the one contribution from the score on demand, so a
  // round writes one column instead of three (the square root of chi^2 alone was a quarter of
  // its time).
  enum class MagnitudeSource : std::uint8_t { Stored, Score, SqrtScore };
  MagnitudeSource magnitude_source_ = MagnitudeSource::Stored;
  bool contribution_is_score_ = false;
  Index n_ = 0;
  Index n_features_ = 0;
  std::vector<Scalar> score_, magnitude_, contribution_, coherence_;
  std::vector<std::uint8_t> inlier_;
  const char* feature_names_[4] = {"", "", "", ""};
  Scalar threshold_ = 0;
  const char* unit_ = "";
  const char* magnitude_unit_ = "";
  Scalar magnitude_cut_ = std::numeric_limits<Scalar>::quiet_NaN();
  Scalar noise_scale_ = std::numeric_limits<Scalar>::quiet_NaN();
  Index n_evidence_ = 0;
  Index n_inliers_ = 0, n_flagged_ = 0, n_flagged_rejected_ = 0, n_floor_ = 0, n_fitted_ = 0;
  ResidualField<Scalar> field_{};
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

  /// Screens one frame: one round. The result stays valid until the next call on this object.
  /// \throws InvalidArgument when there are no matches.
  const ScreenResult<Scalar>& screen(const Matches<Scalar>& matches) {
    run(matches);
    return result_;
  }

  /// The last result.
  [[nodiscard]] const ScreenResult<Scalar>& result() const { return result_; }

  /// Grows every buffer for frames of up to `n` matches, and the magnitude histogram to the most
  /// bins its config can produce (FixedWidth: magnitude_clip / width), so that not even the first
  /// frame of that size allocates.
  void reserve(Index n) {
    detail::require(n >= 1 && n <= (Index{1} << 31), "reserve needs n in [1, 2^31], got ", n);
    const auto k = static_cast<std::size_t>(n);
    for (auto* v : {&result_.score_, &result_.magnitude_, &angle_, &fit_values_, &scratch_, &dx_,
                    &dy_, &depth_, &coherence_, &proximity_, &history_})
      v->reserve(k);
    flagged_index_.reserve(k);
    result_.contribution_.reserve(4 * k);
    result_.inlier_.reserve(k);
    for (auto* v : {&angle_used_, &fired_, &looks_static_}) v->reserve(k);
    cell_of_.reserve(k);
    result_.coherence_.reserve(k);
    detail::CoherenceWork<Scalar>& w = coherence_work_;
    for (auto* v : {&w.dx, &w.dy, &w.layer, &w.kx, &w.ky, &w.nsx, &w.nsy, &w.ncount, &w.sub_dx,
                    &w.sub_dy, &w.sub_llr})
      v->reserve(k);
    w.support.reserve(k);
    w.cell.reserve(k);
    for (auto* v : {&w.sx, &w.sy, &w.count, &w.tx, &w.ty, &w.tcount})
      v->reserve(detail::kMaxCoherenceCells);
    cell_counts_.reserve(detail::kMaxBalanceCells);
    cell_factor_.reserve(detail::kMaxBalanceCells);
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
      // The evidence histograms: values in [0, 64], bins no narrower than 0.1.
      evidence_hist_.reserve(641);
      // A rigid refit's rows (15 doubles a match) only where this config asks for it; a caller
      // that switches to one later (later_rounds_config) allocates them on its first frame.
      if (s->field.refit_model == RefitModel::Rigid) rigid_work_.reserve(k);
    }
  }

 private:
  using Column = Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>;
  void run(const Matches<Scalar>& matches);
  void prepare(const Matches<Scalar>& matches, Index n_features);
  void run_hbos(const Matches<Scalar>& matches, const HbosScreen& s);
  void run_gated(const Matches<Scalar>& matches, const HbosScreen& s);
  void run_gate(const Matches<Scalar>& matches);
  void finish(const Matches<Scalar>& matches, Scalar floor);
  void finish(const Matches<Scalar>& matches, Scalar floor, const Scalar* magnitude);
  template <class Use>
  void fit_field(const Matches<Scalar>& matches, const HbosScreen& s, const Use& use, double window,
                 ResidualCenter center);
  void centred_magnitudes(const Matches<Scalar>& matches, const HbosScreen& s);
  /// The loop of centred_magnitudes, with c(p_i) = centre(i).
  template <class Centre>
  void centred_magnitudes(const Matches<Scalar>& matches, const HbosScreen& s,
                          const Centre& centre);
  /// The balanced weight (samples_, as fit_field left it) of the fit set's matches whose
  /// whitened residual lies within `window` of `field`, an affine field (the constant refit).
  [[nodiscard]] Scalar field_support(const Matches<Scalar>& matches,
                                     const ResidualField<Scalar>& field, double window) const;
  /// Steps 3-4: the noise gate, then (unless `evidence` is false: a refit follows that makes
  /// this round's evidence moot) every match's evidence and whether it looks static.
  void gate_and_evidence(const Matches<Scalar>& matches, const HbosScreen& s, bool evidence = true);
  /// CoherenceEvidence::flagged_consensus, after the last evidence round: each flagged match's
  /// coherence taken again over every neighbour inside the gate, and its coherence bit of fired_.
  /// Once per frame: a flagged match is never in the fit set, so never looks static, and an
  /// earlier round's value of it decides nothing.
  void flagged_consensus(const Matches<Scalar>& matches, const HbosScreen& s);
  [[nodiscard]] bool in_fit(const Matches<Scalar>& matches, Index i) const {
    return !fit_unflagged_only_ || !matches.on_dynamic_mask(i);
  }
  /// Copies the values with `use(i)` into fit_values_ and returns them as an Eigen column.
  template <class Use>
  Column select(const Matches<Scalar>& matches, const std::vector<Scalar>& values, const Use& use) {
    Index m = 0;
    for (Index i = 0; i < matches.size(); ++i)
      if (use(i)) fit_values_[static_cast<std::size_t>(m++)] = values[static_cast<std::size_t>(i)];
    return Column(fit_values_.data(), m);
  }
  /// The finite values of the fit set.
  Column finite_fit_column(const Matches<Scalar>& matches, const std::vector<Scalar>& values) {
    return select(matches, values, [&](Index i) {
      return in_fit(matches, i) && std::isfinite(values[static_cast<std::size_t>(i)]);
    });
  }
  /// The values of the fit set.
  Column fit_column(const Matches<Scalar>& matches, const std::vector<Scalar>& values) {
    return select(matches, values, [&](Index i) { return in_fit(matches, i); });
  }

  ScreenConfig config_;
  ScreenResult<Scalar> result_;
  Histogram<Scalar> magnitude_hist_, angle_hist_, evidence_hist_;
  std::vector<Scalar> angle_, fit_values_, scratch_;
  std::vector<Scalar> dx_, dy_, depth_, coherence_, proximity_, history_;
  std::vector<std::uint8_t> angle_used_, fired_, looks_static_;
  detail::RigidFitWork rigid_work_;
  std::vector<std::uint32_t> cell_counts_, cell_of_, flagged_index_;
  std::vector<Scalar> cell_factor_;
  detail::FieldSamples<Scalar> samples_;
  detail::CoherenceWork<Scalar> coherence_work_;
  detail::FieldStart<Scalar> start_;  // the last fit's weighted median, for a refit of its samples
  Scalar gate_ = 0, scale_ = 0;
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
  r.magnitude_source_ = ScreenResult<Scalar>::MagnitudeSource::Stored;
  r.contribution_is_score_ = false;
  fit_values_.resize(k);
  r.field_ = ResidualField<Scalar>{};
  r.magnitude_cut_ = r.noise_scale_ = std::numeric_limits<Scalar>::quiet_NaN();
  r.n_evidence_ = 0;
  r.coherence_.clear();
  // A new frame: the coherence grid of the last one no longer places these matches.
  coherence_work_.grid_valid = false;

  const Index flagged = matches.flagged_count();
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
template <class Use>
void ReprojectionScreen<Scalar>::fit_field(const Matches<Scalar>& matches, const HbosScreen& s,
                                           const Use& use, double window, ResidualCenter center) {
  if (center == ResidualCenter::None) return;
  detail::collect_field_samples(matches, use, samples_);
  if (s.field.balance_cell_px > 0.0)
    detail::balance_by_cell(samples_, s.field.balance_cell_px, cell_counts_, cell_of_,
                            cell_factor_);
  start_.reset();
  result_.field_ = detail::dominant_field(samples_, center, window, s.residuals.center_iterations,
                                          scratch_, &start_);
}

template <class Scalar>
Scalar ReprojectionScreen<Scalar>::field_support(const Matches<Scalar>& matches,
                                                 const ResidualField<Scalar>& field,
                                                 double window) const {
  // samples_ holds the fit set in match order with its balanced weights w = b / sigma^2.
  const auto w2 = static_cast<Scalar>(window * window);
  Scalar support = 0;
  std::size_t k = 0;
  for (Index i = 0; i < matches.size(); ++i) {
    if (!in_fit(matches, i)) continue;
    const Eigen::Matrix<Scalar, 2, 1> d =
        matches.residual(i) - field.affine_at(matches.predicted(i));
    const Scalar s2 = matches.sigma(i) * matches.sigma(i);
    // Outside the window it adds +0, which leaves the sum as it is: no branch.
    support += d.squaredNorm() <= w2 * s2 ? samples_.w[k] * s2 : Scalar(0);
    ++k;
  }
  return support;
}

template <class Scalar>
void ReprojectionScreen<Scalar>::centred_magnitudes(const Matches<Scalar>& matches,
                                                    const HbosScreen& s) {
  const auto n = static_cast<std::size_t>(matches.size());
  dx_.resize(n);
  dy_.resize(n);
  // The field's model is decided once, outside the loop over the matches.
  const ResidualField<Scalar> field = result_.field_;
  if (field.rigid) {
    centred_magnitudes(matches, s, [&](Index i) {
      return field.at(matches.predicted(i), inverse_depth_of(matches.depth(i)));
    });
  } else {
    centred_magnitudes(matches, s, [&](Index i) { return field.affine_at(matches.predicted(i)); });
  }
}

template <class Scalar>
template <class Centre>
void ReprojectionScreen<Scalar>::centred_magnitudes(const Matches<Scalar>& matches,
                                                    const HbosScreen& s, const Centre& centre) {
  ScreenResult<Scalar>& r = result_;
  const Index n = matches.size();
  const auto clip = static_cast<Scalar>(s.magnitude_clip);
  for (Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Eigen::Matrix<Scalar, 2, 1> c = centre(i);
    Eigen::Matrix<Scalar, 2, 1> d = matches.residual(i) - c;
    // A stereo component shifts with the pose error like u does: center it by c_x.
    const Scalar right = matches.has_right(i) ? matches.right_residual(i) - c.x() : Scalar(0);
    Scalar m = std::sqrt(d.squaredNorm() + right * right);
    if (s.residuals.whiten) {
      m /= matches.sigma(i);
      d /= matches.sigma(i);
    }
    if (!std::isfinite(m) || !d.allFinite()) {
      // A residual that overflows (or a field fitted to such residuals) has no direction and
      // the largest magnitude: it can only be rejected, and it must not poison its neighbours.
      m = std::numeric_limits<Scalar>::max();
      d.setZero();
    }
    if (clip > Scalar(0)) m = std::min(m, clip);
    r.magnitude_[k] = m;
    dx_[k] = d.x();
    dy_[k] = d.y();
  }
}

template <class Scalar>
void ReprojectionScreen<Scalar>::run_hbos(const Matches<Scalar>& matches, const HbosScreen& s) {
  if (s.gate.enabled) {
    run_gated(matches, s);
    return;
  }
  const Index n_features = s.angle == AngleFeature::None ? 1 : 2;
  prepare(matches, n_features);
  ScreenResult<Scalar>& r = result_;
  const Index n = matches.size();
  const auto un = static_cast<std::size_t>(n);
  r.feature_names_[0] = "magnitude";
  r.feature_names_[1] = "angle";
  r.unit_ = "score";
  r.magnitude_unit_ = s.residuals.whiten ? "px/sigma" : "px";

  // 1-2. Center, magnitude (clipped), angle.
  fit_field(
      matches, s, [&](Index i) { return in_fit(matches, i); }, s.residuals.center_window,
      s.residuals.center);
  centred_magnitudes(matches, s);
  angle_.resize(un);
  if (s.angle != AngleFeature::None)
    for (std::size_t k = 0; k < un; ++k) angle_[k] = std::atan2(dy_[k], dx_[k]);

  // 3. Histograms fitted on the fit set; contributions for every match. A clipped magnitude is
  // beyond any bin that means something: it is not fitted (a crowd of gross mismatches at the
  // clip would otherwise become the modal bin and score 0) and it scores the cap.
  const auto clip = static_cast<Scalar>(s.magnitude_clip);
  const auto clipped = [&](Index i) {
    return clip > Scalar(0) && r.magnitude_[static_cast<std::size_t>(i)] >= clip;
  };
  const Column unclipped =
      select(matches, r.magnitude_, [&](Index i) { return in_fit(matches, i) && !clipped(i); });
  Scalar* c_mag = r.contribution_.data();
  if (unclipped.size() == 0) {
    // Every fitted match is a gross mismatch: nothing is trusted.
    std::fill(r.score_.begin(), r.score_.end(), Scalar(1));
    std::fill(r.contribution_.begin(), r.contribution_.end(), Scalar(0));
    std::fill(c_mag, c_mag + n, Scalar(1));
    r.threshold_ = Scalar(0);
    finish(matches, Scalar(0));
    return;
  }
  magnitude_hist_.refit(unclipped, s.magnitude, s.scoring, scratch_, 0);
  for (Index i = 0; i < n; ++i) {
    c_mag[i] = clipped(i) ? magnitude_hist_.cap()
                          : magnitude_hist_.contribution(r.magnitude_[static_cast<std::size_t>(i)]);
  }
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
    if (m > 0)
      angle_hist_.refit(Column(fit_values_.data(), m), s.angle_spec, s.scoring, scratch_, 1);
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
void ReprojectionScreen<Scalar>::gate_and_evidence(const Matches<Scalar>& matches,
                                                   const HbosScreen& s, bool evidence) {
  ScreenResult<Scalar>& r = result_;
  const Index n = matches.size();
  const auto un = static_cast<std::size_t>(n);
  // 3. The noise scale over the fit set and the gate.
  const Column fit = fit_column(matches, r.magnitude_);
  scratch_.assign(fit.data(), fit.data() + fit.size());
  scale_ = std::max(detail::rayleigh_scale(scratch_, scratch_.size(), s.gate.scale_quantile),
                    static_cast<Scalar>(s.gate.min_scale));
  // A frame whose residuals are all exactly zero has no noise to measure: with min_scale 0 the
  // floor decides.
  const auto floor = static_cast<Scalar>(s.gate.floor);
  gate_ = std::max(floor, static_cast<Scalar>(s.gate.scales) * scale_);
  const Scalar s_eff = std::max(scale_, floor * Scalar(1e-3));
  if (!evidence) return;

  // 4. Evidence.
  coherence_.assign(un, Scalar(0));
  if (s.coherence.enabled) {
    detail::CoherenceWork<Scalar>& w = coherence_work_;
    w.dx = dx_;
    w.dy = dy_;
    w.support.resize(un);
    for (Index i = 0; i < n; ++i)
      w.support[static_cast<std::size_t>(i)] =
          in_fit(matches, i) && r.magnitude_[static_cast<std::size_t>(i)] <= gate_ ? 1 : 0;
    scratch_.resize(un);
    depth_.resize(un);
    fit_values_.resize(un);
    for (Index i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const Eigen::Matrix<Scalar, 2, 1> p = matches.predicted(i);
      scratch_[k] = p.x();
      fit_values_[k] = p.y();
      depth_[k] = matches.depth(i);
    }
    detail::coherence_evidence(scratch_.data(), fit_values_.data(), depth_.data(), un, gate_, s_eff,
                               s.coherence.cell_px, s.coherence.depth_ratio, s.coherence.z0, w,
                               coherence_.data());
    // Bounded like the magnitude: it bounds the evidence histogram's bins.
    for (Scalar& l : coherence_) l = std::min(l, Scalar(64));
  }
  proximity_.assign(un, Scalar(0));
  history_.assign(un, Scalar(0));
  fired_.assign(un, 0);
  looks_static_.assign(un, 0);
  const auto mask_radius = static_cast<Scalar>(s.mask.radius_px);
  const Scalar mask_floor = static_cast<Scalar>(s.mask.min_scales) * s_eff;
  // A residual this close to the background is what the frame's own noise gives: the history
  // alone does not overrule it, or a static chain rejected once would stay rejected.
  const Scalar history_floor = static_cast<Scalar>(s.history.min_scales) * s_eff;
  for (Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    std::uint8_t fired = 0;
    if (s.coherence.enabled && coherence_[k] > static_cast<Scalar>(s.coherence.floor)) fired |= 1;
    const Scalar d = matches.mask_distance(i);
    if (s.mask.enabled && !std::isnan(d)) {
      proximity_[k] = std::max(Scalar(0), Scalar(1) - d / mask_radius);
      if (proximity_[k] > Scalar(0) && r.magnitude_[k] > mask_floor) fired |= 2;
    }
    const Scalar h = matches.outlier_history(i);
    if (s.history.enabled && !std::isnan(h)) {
      history_[k] = h;
      if (h > static_cast<Scalar>(s.history.floor) && r.magnitude_[k] > history_floor) fired |= 4;
    }
    fired_[k] = fired;
    looks_static_[k] = in_fit(matches, i) && r.magnitude_[k] <= gate_ && fired == 0 ? 1 : 0;
  }
}

template <class Scalar>
void ReprojectionScreen<Scalar>::flagged_consensus(const Matches<Scalar>& matches,
                                                   const HbosScreen& s) {
  const Index n = matches.size();
  const auto un = static_cast<std::size_t>(n);
  detail::CoherenceWork<Scalar>& w = coherence_work_;
  // The last round's residuals (w.dx, w.dy), gate and scale, and the frame's grid (still valid:
  // scratch_, fit_values_ and depth_ hold its pixels and depths, untouched since).
  for (std::size_t k = 0; k < un; ++k) w.support[k] = result_.magnitude_[k] <= gate_ ? 1 : 0;
  // Only the flagged matches' consensus is taken again (into their own entries of coherence_);
  // every match still supports its neighbours.
  flagged_index_.clear();
  for (Index i = 0; i < n; ++i)
    if (matches.on_dynamic_mask(i)) flagged_index_.push_back(static_cast<std::uint32_t>(i));
  const Scalar s_eff = std::max(scale_, static_cast<Scalar>(s.gate.floor) * Scalar(1e-3));
  detail::coherence_evidence(scratch_.data(), fit_values_.data(), depth_.data(), un, gate_, s_eff,
                             s.coherence.cell_px, s.coherence.depth_ratio, s.coherence.z0, w,
                             coherence_.data(), &flagged_index_);
  const auto floor = static_cast<Scalar>(s.coherence.floor);
  for (const std::uint32_t k : flagged_index_) {
    coherence_[k] = std::min(coherence_[k], Scalar(64));  // bounded as in the rounds
    fired_[k] = static_cast<std::uint8_t>((fired_[k] & ~1U) | (coherence_[k] > floor ? 1U : 0U));
  }
}

template <class Scalar>
void ReprojectionScreen<Scalar>::run_gated(const Matches<Scalar>& matches, const HbosScreen& s) {
  constexpr Index kFeatures = 4;  // magnitude, coherence, mask, history
  prepare(matches, kFeatures);
  ScreenResult<Scalar>& r = result_;
  const Index n = matches.size();
  const auto un = static_cast<std::size_t>(n);
  r.feature_names_[0] = "magnitude";
  r.feature_names_[1] = "coherence";
  r.feature_names_[2] = "mask";
  r.feature_names_[3] = "history";
  r.unit_ = "score";
  r.magnitude_unit_ = "px/sigma";

  // 1-5. Field, magnitudes, gate, evidence; then once more with the field fitted on the matches
  // that look static.
  // The first passes fit a constant field: an affine one can tilt into a ramp that absorbs a
  // compact object on one side of the image (its gradient then hides the object's motion). The
  // configured field is fitted last, on the matches that look static.
  const auto fit_set = [&](Index i) { return in_fit(matches, i); };
  const ResidualCenter first_center =
      s.residuals.center == ResidualCenter::None ? ResidualCenter::None : ResidualCenter::Constant;
  fit_field(matches, s, fit_set, s.residuals.center_window, first_center);
  centred_magnitudes(matches, s);
  // With a field, only this round's noise scale is used: the rounds below redo the evidence.
  gate_and_evidence(matches, s, s.residuals.center == ResidualCenter::None);
  if (s.residuals.center != ResidualCenter::None) {
    // The wide first window lets a person a few noise levels off the background join the fit;
    // refit with a window of the noise this frame has. The fit set and its balanced weights are
    // those of the first fit, so are the weighted median the mean shift starts from: only the
    // window changes.
    const double window =
        std::max(std::min(s.residuals.center_window,
                          s.field.refit_window_scales * static_cast<double>(scale_)),
                 1e-3);
    result_.field_ = detail::dominant_field(samples_, first_center, window,
                                            s.residuals.center_iterations, scratch_, &start_);
    // A fitted field can still settle between the background and a large, slow object; the
    // rough pose's own frame (no field) is the other candidate. Keep the one more matches of
    // the fit set support within the window, each image cell counted as balanced.
    if (field_support(matches, result_.field_, window) <
        field_support(matches, ResidualField<Scalar>{}, window))
      result_.field_ = ResidualField<Scalar>{};
    centred_magnitudes(matches, s);
    gate_and_evidence(matches, s);
  }
  if (s.field.refit_on_static && s.residuals.center != ResidualCenter::None) {
    Index n_static = 0;
    for (const std::uint8_t b : looks_static_) n_static += b;
    if (n_static >= config_.min_fit_matches) {
      // Whitened pixels, like center_window; never wider than it.
      const double window = std::min(s.residuals.center_window,
                                     s.field.refit_window_scales * static_cast<double>(scale_));
      const auto looks_static = [&](Index i) {
        return looks_static_[static_cast<std::size_t>(i)] != 0;
      };
      fit_field(matches, s, looks_static, std::max(window, 1e-3), s.residuals.center);
      // The rigid field starts from the affine one's support, weighted by 1/sigma^2 alone: the
      // matches that look static are spread over the image already.
      if (s.field.refit_model == RefitModel::Rigid)
        result_.field_ = detail::fit_rigid_field(matches, looks_static, result_.field_,
                                                 s.field.camera, std::max(window, 1e-3),
                                                 s.residuals.center_iterations, rigid_work_);
      centred_magnitudes(matches, s);
      gate_and_evidence(matches, s);
    }
  }

  if (s.coherence.enabled && s.coherence.flagged_consensus && fit_unflagged_only_)
    flagged_consensus(matches, s);

  // 6. Histograms of the evidence on the matches that look static; the fired features' sum.
  const auto t = static_cast<Scalar>(std::get<FixedThreshold>(s.threshold).value);
  const auto on_static = [&](Index i) { return looks_static_[static_cast<std::size_t>(i)] != 0; };
  const Column static_magnitudes = select(matches, r.magnitude_, on_static);
  const bool have_static = static_magnitudes.size() >= 2;
  std::fill(r.contribution_.begin(), r.contribution_.end(), Scalar(0));
  const FeatureSpec evidence_spec = [] {
    FeatureSpec spec;
    spec.binning.method = BinningMethod::FixedWidth;
    spec.binning.origin = 0.0;
    spec.tail = Tail::Upper;
    return spec;
  }();
  // The magnitude first: `static_magnitudes` lives in fit_values_, which each charge below
  // overwrites with its own feature's values.
  if (have_static) {
    magnitude_hist_.refit(static_magnitudes, s.magnitude, s.scoring, scratch_, 0);
    for (std::size_t k = 0; k < un; ++k)
      if (fired_[k]) r.contribution_[k] = magnitude_hist_.contribution(r.magnitude_[k]);
  }
  // A fired feature without a static population to compare with scores above any cut.
  const Scalar no_reference = t + Scalar(1);
  auto charge = [&](Index feature, const std::vector<Scalar>& values, std::uint8_t bit,
                    double width, Scalar floor) {
    Scalar* out = r.contribution_.data() + feature * n;
    // (Stops at the first: most frames fire on few matches, many on none.)
    if (std::none_of(fired_.begin(), fired_.end(),
                     [bit](std::uint8_t f) { return (f & bit) != 0; }))
      return;
    if (!have_static) {
      for (std::size_t k = 0; k < un; ++k)
        if (fired_[k] & bit) out[k] = no_reference;
      return;
    }
    FeatureSpec spec = evidence_spec;
    spec.binning.width = width;
    const Column reference = select(matches, values, on_static);
    // Only the upper tail is scored, so how far below the floor a static match's evidence lies
    // carries nothing; counted at the floor, the bins stay bounded (a coherence of -3e4, a
    // static match beside a cluster of gross mismatches, once needed 1.3e5 bins and threw).
    for (Index i = 0; i < reference.size(); ++i) {
      Scalar& v = fit_values_[static_cast<std::size_t>(i)];
      v = std::max(v, floor);
    }
    evidence_hist_.refit(reference, spec, s.scoring, scratch_, feature);
    for (std::size_t k = 0; k < un; ++k)
      if (fired_[k] & bit) out[k] = evidence_hist_.contribution(values[k]);
  };
  // Coherence is a log-likelihood ratio: below -64 (odds of e^64 for the background) every value
  // says the same. Proximity and history lie in [0, 1].
  charge(1, coherence_, 1, 0.5, Scalar(-64));
  charge(2, proximity_, 2, 0.1, Scalar(0));
  charge(3, history_, 4, 0.1, Scalar(0));

  // 7. Decision statistic: max(t m / G, E); the cut t.
  Index by_evidence = 0;
  // The least score above t, once per frame (a libm call per match otherwise).
  const Scalar above = std::nextafter(t, std::numeric_limits<Scalar>::infinity());
  for (std::size_t k = 0; k < un; ++k) {
    Scalar e = 0;
    for (Index j = 0; j < kFeatures; ++j)
      e += r.contribution_[static_cast<std::size_t>(j) * un + k];
    // score > t exactly when the magnitude is beyond the gate, whatever t and G (even inf).
    const Scalar m = r.magnitude_[k];
    Scalar g = t * (m / gate_);
    if (m > gate_) {
      g = std::isnan(g) ? above : std::max(g, above);
    } else if (std::isnan(g)) {
      g = t;
    }
    r.score_[k] = std::max(g, e);
    if (g <= t && e > t) ++by_evidence;
  }
  r.threshold_ = t;
  r.magnitude_cut_ = gate_;
  r.noise_scale_ = scale_;
  r.n_evidence_ = by_evidence;
  r.coherence_.assign(coherence_.begin(), coherence_.end());
  finish(matches, Scalar(0));
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
  // The fixed gate compares |r|^2 with max_px^2, as chi^2 does: no square root per match.
  if (std::holds_alternative<FixedPixelGate>(strategy)) stat = {false, true, "residual_px_squared"};
  if (const auto* q = std::get_if<QuantileGate>(&strategy)) stat.whiten = q->whiten;
  if (const auto* g = std::get_if<MadGate>(&strategy)) stat.whiten = g->whiten;
  if (stat.whiten && !stat.squared) stat.name = "residual_whitened";
  r.feature_names_[0] = stat.name;
  r.magnitude_unit_ = stat.whiten ? "px/sigma" : "px";
  r.unit_ = stat.squared ? (stat.whiten ? "px^2/sigma^2" : "px^2") : r.magnitude_unit_;

  // The statistic over whole columns (Eigen arrays: SIMD arithmetic; a scalar std::sqrt loop
  // keeps its errno branch and does not vectorise), weighted by the information 1/sigma^2 the
  // matches keep (a multiply, not a division). Stereo components are added in a second pass
  // that frames without stereo matches skip.
  const auto* chi = std::get_if<ChiSquareGate>(&strategy);
  using Array = Eigen::Array<Scalar, Eigen::Dynamic, 1>;
  using Source = typename ScreenResult<Scalar>::MagnitudeSource;
  const Eigen::Map<const Array> px(matches.predicted_x_.data(), n);
  const Eigen::Map<const Array> py(matches.predicted_y_.data(), n);
  const Eigen::Map<const Array> ox(matches.observed_x_.data(), n);
  const Eigen::Map<const Array> oy(matches.observed_y_.data(), n);
  const Eigen::Map<const Array> information(matches.information_.data(), n);
  Eigen::Map<Array> score(r.score_.data(), n), magnitude(r.magnitude_.data(), n);
  const bool stereo = matches.stereo_count() > 0;
  if (stat.whiten && !stereo) {
    score = ((ox - px).square() + (oy - py).square()) * information;  // e^2 / sigma^2
  } else {
    score = (ox - px).square() + (oy - py).square();  // e^2 [px^2]
    if (stereo) {
      for (Index i = 0; i < n; ++i) {
        const Scalar right = matches.right_residual(i);  // 0 without a stereo component
        score(i) += right * right;
      }
    }
    if (stat.whiten) score *= information;
  }
  // Eigen's float square root is an approximation under EIGEN_FAST_MATH (rsqrt and a Newton
  // step: not correctly rounded, and NaN at inf); double's is the exact sqrtpd.
  // (Coefficient-wise into a mapped buffer: no temporary, so no allocation.)
  const auto sqrt_into = [](Eigen::Map<Array>& out, const Eigen::Map<Array>& in) {
    if constexpr (std::is_same_v<Scalar, double>) {
      out = in.sqrt();
    } else {
      out = in.unaryExpr([](Scalar v) { return std::sqrt(v); });
    }
  };
  if (stat.squared) {
    // The magnitude (|r|/sigma for chi^2, |r| for the fixed gate) is the score's square root:
    // taken on demand, unless stereo matches' chi^2 is rescaled below (then it is stored first).
    r.magnitude_source_ = Source::SqrtScore;
    if (chi != nullptr && stereo) {
      sqrt_into(magnitude, score);
      r.magnitude_source_ = Source::Stored;
      // One threshold for mixed frames: a stereo match's chi^2 is rescaled to the 2-dof gate.
      const auto ratio = static_cast<Scalar>(chi->chi2_mono / chi->chi2_stereo);
      for (Index i = 0; i < n; ++i)
        if (matches.has_right(i) && std::isfinite(score(i))) score(i) *= ratio;  // inf stays inf
    }
  } else {
    sqrt_into(score, score);
    r.magnitude_source_ = Source::Score;
  }
  r.contribution_is_score_ = true;

  if (const auto* g = std::get_if<FixedPixelGate>(&strategy)) {
    r.threshold_ = static_cast<Scalar>(g->max_px * g->max_px);
  } else if (chi != nullptr) {
    r.threshold_ = static_cast<Scalar>(chi->chi2_mono);
  } else if (const auto* q = std::get_if<QuantileGate>(&strategy)) {
    // Overflowed residuals (inf; never kept, see finish) are no measurement of the frame's
    // spread: the quantile and the MAD are taken over the finite ones.
    // (fit_values_ is this frame's copy already: the selection may reorder it in place)
    const Index m = finite_fit_column(matches, r.score_).size();
    r.threshold_ = m == 0 ? std::numeric_limits<Scalar>::infinity()
                          : detail::numpy_percentile_linear(fit_values_.data(),
                                                            fit_values_.data() + m, q->quantile);
  } else {
    const auto& mad = std::get<MadGate>(strategy);
    const auto column = finite_fit_column(matches, r.score_);
    r.threshold_ = column.size() == 0 ? std::numeric_limits<Scalar>::infinity()
                                      : compute_threshold(column, MedianMad{mad.k, true}, scratch_);
  }
  r.magnitude_cut_ = stat.squared ? std::sqrt(r.threshold_) : r.threshold_;
  finish(matches, Scalar(0),
         r.magnitude_source_ == Source::Stored ? r.magnitude_.data() : r.score_.data());
}

template <class Scalar>
void ReprojectionScreen<Scalar>::finish(const Matches<Scalar>& matches, Scalar floor) {
  finish(matches, floor, result_.magnitude_.data());
}

/// The decisions from the scores and `magnitude` (the stored magnitudes, or any column with the
/// same finiteness and the same sign against `floor`: the score itself for chi^2, whose square
/// root is the magnitude).
template <class Scalar>
void ReprojectionScreen<Scalar>::finish(const Matches<Scalar>& matches, Scalar floor,
                                        const Scalar* magnitude) {
  ScreenResult<Scalar>& r = result_;
  const bool reject_flagged = config_.flagged == FlaggedPolicy::Reject;
  const Scalar threshold = r.threshold_;
  // Raw pointers, read once: stores through the uint8_t decisions may alias anything, so the
  // vectors' data pointers would otherwise be reloaded every iteration (that and the branches
  // were 40 % of a gate's time).
  const std::uint8_t* flag = matches.flag_.data();
  const Scalar* score = r.score_.data();
  std::uint8_t* inlier = r.inlier_.data();
  const auto n = static_cast<std::size_t>(matches.size());
  // Branch-free: the decisions of a frame are data, not control flow. The decision pass writes
  // one byte per match and nothing else; the counts are taken from those bytes after (counting in
  // the pass itself, three counters beside the byte stores, made the vectorised loop widen,
  // shuffle and spill: 60 % of a gate's time). GCC 12 vectorises a double comparison stored as
  // a byte only when the loop also reads a byte, hence the flag in every form of the loop.
  const std::uint8_t veto = reject_flagged ? 0xFF : 0x00;
  const bool one_comparison = magnitude == score && std::isfinite(threshold) && floor <= threshold;
  if (one_comparison) {
    // A gate's statistic is its own magnitude: below a finite threshold it is finite, and at or
    // under the floor it is below the threshold, so the rule is one comparison.
    for (std::size_t k = 0; k < n; ++k)
      inlier[k] = static_cast<std::uint8_t>((score[k] <= threshold) & ((flag[k] & veto) == 0));
  } else {
    // Bit 0: kept; bit 1: kept by the floor (cleared below, once counted).
    for (std::size_t k = 0; k < n; ++k) {
      const Scalar m = magnitude[k];
      // A residual that overflowed is never kept, whatever the rule says of its score.
      const bool below = (score[k] <= threshold) & std::isfinite(m);
      const bool floored = !below & (m <= floor);
      const bool keep = (below | floored) & ((flag[k] & veto) == 0);
      inlier[k] = static_cast<std::uint8_t>(static_cast<unsigned>(keep) |
                                            (static_cast<unsigned>(keep & floored) << 1U));
    }
  }
  // Byte passes (16 matches a vector), counting in 32 bits per chunk.
  Index kept = 0, floor_kept = 0, flagged_rejected = 0;
  constexpr std::size_t chunk = std::size_t{1} << 30;
  const bool any_flagged = matches.flagged_count() > 0;
  for (std::size_t begin = 0; begin < n; begin += chunk) {
    const std::size_t end = std::min(n, begin + chunk);
    if (!one_comparison) {
      std::uint32_t floor32 = 0;
      for (std::size_t k = begin; k < end; ++k)
        floor32 += static_cast<std::uint32_t>(inlier[k] >> 1U);
      for (std::size_t k = begin; k < end; ++k) inlier[k] &= 1U;
      floor_kept += floor32;
    }
    std::uint32_t kept32 = 0;
    for (std::size_t k = begin; k < end; ++k) kept32 += inlier[k];
    kept += kept32;
    if (any_flagged) {
      std::uint32_t flagged32 = 0;
      for (std::size_t k = begin; k < end; ++k)
        flagged32 += static_cast<std::uint32_t>((inlier[k] ^ 1U) & (flag[k] != 0 ? 1U : 0U));
      flagged_rejected += flagged32;
    }
  }
  r.n_inliers_ = kept;
  r.n_floor_ = floor_kept;
  r.n_flagged_rejected_ = flagged_rejected;
}

}  // namespace hbos
