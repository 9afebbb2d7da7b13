#pragma once
/// \file
/// The strategies a reprojection screen can use, behind one variant so that an ablation swaps
/// them with one assignment: the HBOS screen (in its default and its literal `paper` form) and
/// the baselines it is measured against.
///
/// Each strategy rejects match i when:
/// - HbosScreen: its HBOS score on residual features > the threshold (this library; `paper()` =
///   the HBOS-SLAM paper).
/// - FixedPixelGate: |r_i| > max_px (common practice).
/// - ChiSquareGate: |r_i|^2 / sigma_i^2 > 5.991 (2 dof) or 7.815 (3 dof) (ORB-SLAM2,
///   Optimizer::PoseOptimization).
/// - QuantileGate: |r_i| > the 0.8 quantile of |r| over unflagged matches (CFP-SLAM's adaptive
///   threshold).
/// - MadGate: |r_i| / sigma_i > median + k * 1.4826 * MAD (robust z-score).
///
/// Each strategy's `score` is its decision statistic (higher = worse) and its threshold the
/// cut on it, so results of every strategy read the same way.
///
/// Why the default HbosScreen is what it is — each choice measured by examples/screening_study
/// (docs/screening.md; mixed leakage 5 %, single screen, statics dropped / dynamics kept):
/// - **Centered on the dominant residual field** (affine): under a rough pose every static match
///   shares a coherent shift; without centering 7.5 / 26.1 %, constant center 8.1 / 16.4 %,
///   affine 8.0 / 14.1 %.
/// - **Magnitude whitened by sigma** (px/sigma): ORB keypoint noise is proportional to 1.2^octave
///   (measured on TUM fr1/xyz); raw pixels drop 12.2 % of statics instead of 8.0 %.
/// - **Fixed-width bins anchored at zero** (0.25 px/sigma, half the measured keypoint noise):
///   10 equal-width bins over [min, max] are stretched by gross mismatches and keep 70 % of
///   dynamics.
/// - **One-sided (Upper tail) magnitude**: a match that fits better than typical scores 0; the
///   score never decreases with the residual, so a dense secondary mode beyond a sparse bin (a
///   walking person) is rejected as a whole.
/// - **No angle feature**: over every residual it inverts the logic (random directions of good
///   matches look rare; 11.7 % statics dropped); above the noise it changes nothing.
/// - **A fixed score threshold** of 1.5 (a bin density below 22 % of the mode's, or beyond such a
///   bin), not eq. 6: `0.7 (max - min) + min` follows the most extreme score (34.5 % dynamics
///   kept).
/// - **No noise floor** by default: never rejecting inside chi^2's gate would cap the static loss
/// at
///   chi^2's but keeps twice the dynamics (29.7 %); `keep_below` turns it on.
///
/// Threading: these are plain parameter structs.

#include <Eigen/Core>
#include <cmath>
#include <variant>

#include "hbos/binning.hpp"
#include "hbos/error.hpp"
#include "hbos/histogram.hpp"
#include "hbos/screening/residual_field.hpp"
#include "hbos/threshold.hpp"

namespace hbos {

/// Which angle evidence the HBOS screen adds to the magnitude.
enum class AngleFeature {
  None,        ///< magnitude only (the default)
  Raw,         ///< atan2 of every residual, an independent histogram (the paper)
  AboveNoise,  ///< angle histogram built from, and charged to, residuals above `angle_gate` only
};

/// The HBOS screen on reprojection residuals. Default-constructed = the recommended screen; see
/// the file comment for the reasons and `paper()` for the literal method.
struct HbosScreen {
  ResidualOptions residuals{};  ///< whitening and centering of the residuals
  /// Binning of the magnitude: fixed width [px/sigma, or px when not whitened], anchored at zero,
  /// one-sided.
  FeatureSpec magnitude = [] {
    FeatureSpec spec;
    spec.binning.method = BinningMethod::FixedWidth;
    spec.binning.width = 0.25;
    spec.binning.origin = 0.0;
    spec.tail = Tail::Upper;
    return spec;
  }();
  /// [px/sigma or px] magnitudes are clipped here before binning: everything beyond is an outlier
  /// anyway, and it bounds the bin count (and so the memory) whatever the input.
  double magnitude_clip = 64.0;
  AngleFeature angle = AngleFeature::None;     ///< angle evidence
  FeatureSpec angle_spec = angle_feature(16);  ///< binning of the angle [rad]
  double angle_gate = 2.447;  ///< [px/sigma] AboveNoise: only residuals above this carry an angle
  ScoringOptions scoring{};   ///< empty-bin rule of the histograms
  /// The cut on the summed score. FixedThreshold{t} rejects bins whose density is below
  /// exp(-t) of the modal bin's.
  ThresholdRule threshold = FixedThreshold{1.5};
  /// [px/sigma] noise floor: a match whose (centered, whitened) magnitude is at most this is never
  /// rejected; 0 (the default) disables it. 2.447 = sqrt(5.991) would keep everything ORB-SLAM2's
  /// chi^2 gate keeps around the dominant residual (measured: it lets ~2x more dynamics through).
  double keep_below = 0.0;

  /// The paper's screen taken literally: raw pixel magnitude and raw angle, independent
  /// histograms of 10 equal-width bins over [min, max], two-sided, no centering, threshold
  /// eq. 6 `0.7 (max - min) + min`. For reproduction and comparison only (see docs/screening.md).
  [[nodiscard]] static HbosScreen paper() {
    HbosScreen s;
    s.residuals.whiten = false;
    s.residuals.center = ResidualCenter::None;
    s.magnitude = FeatureSpec{};
    s.magnitude.binning.method = BinningMethod::EqualWidth;
    s.magnitude.binning.rule = BinCountRule::Fixed;
    s.magnitude.binning.bins = 10;
    s.magnitude.tail = Tail::Both;
    s.magnitude_clip = 0.0;
    s.angle = AngleFeature::Raw;
    s.angle_spec = FeatureSpec{};  // the literal method: a plain, non-periodic angle histogram
    s.angle_spec.binning.bins = 10;
    s.threshold = AdaptiveRange{0.7};
    s.keep_below = 0.0;
    return s;
  }
};

/// Reject matches whose residual exceeds a fixed number of pixels.
struct FixedPixelGate {
  double max_px = 3.0;  ///< [px] largest residual kept, > 0
};

/// ORB-SLAM2's gate: reject when |r|^2 / sigma^2 exceeds the 95 % chi^2 quantile of the
/// residual's degrees of freedom (2 for monocular matches, 3 for stereo / RGB-D ones).
struct ChiSquareGate {
  double chi2_mono = 5.991;    ///< 2 dof, 95 %
  double chi2_stereo = 7.815;  ///< 3 dof, 95 %
};

/// CFP-SLAM's adaptive threshold: the `quantile` of the residual magnitudes [px] of the matches
/// off the dynamic mask; every match above it is rejected.
struct QuantileGate {
  double quantile = 0.8;  ///< in (0, 1]
  bool whiten = false;    ///< use |r|/sigma instead of |r| (CFP-SLAM uses pixels)
};

/// Robust z-score gate on the whitened magnitude: median + k * 1.4826 * MAD.
struct MadGate {
  double k = 3.0;      ///< > 0
  bool whiten = true;  ///< use |r|/sigma (true) or |r| [px]
};

/// Any screening strategy; switching is one assignment.
using ScreenStrategy =
    std::variant<HbosScreen, FixedPixelGate, ChiSquareGate, QuantileGate, MadGate>;

/// What a screen does with matches flagged `on_dynamic_mask`.
enum class FlaggedPolicy {
  FitWithout,  ///< flagged matches do not shape histograms, centers or quantiles; judged like any
  Reject,      ///< flagged matches are rejected outright (DynaSLAM-style removal), and not fitted
  Ignore       ///< the flag is ignored
};

/// A strategy plus the screen-wide settings.
struct ScreenConfig {
  ScreenStrategy strategy = HbosScreen{};             ///< the decision rule
  FlaggedPolicy flagged = FlaggedPolicy::FitWithout;  ///< use of the prior
  /// Fitting (histograms, centers, quantiles) needs this many unflagged matches; below it all
  /// matches are fitted. >= 1.
  Eigen::Index min_fit_matches = 10;
};

namespace detail {

inline void validate(const HbosScreen& s) {
  validate(s.residuals);
  validate(s.magnitude, 0);
  require(!s.magnitude.periodic, "HbosScreen magnitude cannot be periodic");
  if (s.angle != AngleFeature::None) validate(s.angle_spec, 1);
  require(s.magnitude_clip >= 0.0 && std::isfinite(s.magnitude_clip),
          "HbosScreen magnitude_clip must be finite and >= 0 (0 = off), got ", s.magnitude_clip);
  require(s.magnitude.binning.method != BinningMethod::FixedWidth || s.magnitude_clip > 0.0,
          "HbosScreen with FixedWidth magnitude bins needs magnitude_clip > 0 to bound the bins");
  require(s.angle_gate >= 0.0 && std::isfinite(s.angle_gate),
          "HbosScreen angle_gate must be finite and >= 0, got ", s.angle_gate);
  require(s.keep_below >= 0.0 && std::isfinite(s.keep_below),
          "HbosScreen keep_below must be finite and >= 0, got ", s.keep_below);
  validate(s.scoring);
  std::visit([](const auto& r) { validate(r); }, s.threshold);
}
inline void validate(const FixedPixelGate& g) {
  require(g.max_px > 0.0 && std::isfinite(g.max_px),
          "FixedPixelGate max_px must be finite and > 0, got ", g.max_px);
}
inline void validate(const ChiSquareGate& g) {
  require(g.chi2_mono > 0.0 && std::isfinite(g.chi2_mono),
          "ChiSquareGate chi2_mono must be finite and > 0, got ", g.chi2_mono);
  require(g.chi2_stereo > 0.0 && std::isfinite(g.chi2_stereo),
          "ChiSquareGate chi2_stereo must be finite and > 0, got ", g.chi2_stereo);
}
inline void validate(const QuantileGate& g) {
  require(g.quantile > 0.0 && g.quantile <= 1.0, "QuantileGate quantile must lie in (0, 1], got ",
          g.quantile);
}
inline void validate(const MadGate& g) {
  require(g.k > 0.0 && std::isfinite(g.k), "MadGate k must be finite and > 0, got ", g.k);
}
inline void validate(const ScreenConfig& c) {
  std::visit([](const auto& s) { validate(s); }, c.strategy);
  require(c.min_fit_matches >= 1, "ScreenConfig min_fit_matches must be >= 1, got ",
          c.min_fit_matches);
}

}  // namespace detail

/// Short name of a strategy, for tables and logs.
[[nodiscard]] inline const char* strategy_name(const ScreenStrategy& s) {
  struct Namer {
    const char* operator()(const HbosScreen&) const { return "hbos"; }
    const char* operator()(const FixedPixelGate&) const { return "fixed"; }
    const char* operator()(const ChiSquareGate&) const { return "chi2"; }
    const char* operator()(const QuantileGate&) const { return "quantile"; }
    const char* operator()(const MadGate&) const { return "mad"; }
  };
  return std::visit(Namer{}, s);
}

}  // namespace hbos
