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
/// Why the default HbosScreen is what it is (each choice measured in docs/screening.md, on the
/// labelled real residual cases and, for the magnitude-only screen, on synthetic scenes):
/// - **Centred on the dominant residual field**: under a rough pose every static match shares a
///   coherent shift; the field is fitted so that a person crowding a few image cells cannot
///   pull it (FieldFit).
/// - **Magnitude whitened by sigma** (px/sigma): ORB keypoint noise grows as 1.2^octave.
/// - **A noise-calibrated gate** (NoiseGate): the real static noise tail is heavier than any
///   fixed model, so a histogram cut on the magnitude alone loses statics that chi^2 keeps; the
///   gate never closes below chi^2's and opens with the frame's own noise.
/// - **Evidence inside the gate** (coherence, mask neighbourhood, history), scored by HBOS
///   against the matches that look static: a person RANSAC absorbed has residuals inside any
///   gate, but they are coherent with their neighbours.
/// - **Fixed-width bins anchored at zero, one-sided**: gross mismatches cannot stretch them, and
///   a match that fits better than typical is never charged.
/// - **No angle feature**: over every residual it inverts the logic (random directions of good
///   matches look rare).
///
/// Threading: these are plain parameter structs.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "hbos/binning.hpp"
#include "hbos/error.hpp"
#include "hbos/histogram.hpp"
#include "hbos/screening/pinhole.hpp"
#include "hbos/screening/residual_field.hpp"
#include "hbos/threshold.hpp"

namespace hbos {

/// Which angle evidence the HBOS screen adds to the magnitude.
enum class AngleFeature {
  None,        ///< magnitude only (the default)
  Raw,         ///< atan2 of every residual, an independent histogram (the paper)
  AboveNoise,  ///< angle histogram built from, and charged to, residuals above `angle_gate` only
};

/// The noise gate of the HBOS screen: a cut on the centred, whitened magnitude m that follows
/// the noise the frame actually has. With s the frame's robust noise scale (the `scale_quantile`
/// quantile of m over the fit set, through the Rayleigh quantile function: 2-D Gaussian noise of
/// scale s per axis gives |d| ~ Rayleigh(s)), never below `min_scale`, the gate is
/// G = max(floor, scales * s). The evidence inside the gate is measured in the same s.
struct NoiseGate {
  bool enabled = true;
  /// [px/sigma] the gate never closes below this. sqrt(5.991): ORB-SLAM2's 95 % chi^2 gate, so
  /// a noise gate alone drops no more static matches than chi^2 does.
  double floor = 2.447;
  /// the gate opens to this many noise scales when the frame is noisier than the floor assumes
  /// (a rough pose whose error the field does not absorb, blur, a heavier-tailed detector);
  /// wider lets mismatches of a few sigma through (docs/screening.md).
  double scales = 3.0;
  /// the quantile the scale is read from, in (0, 1): a low one stays on the static matches
  /// when a dynamic object holds most of the large residuals.
  double scale_quantile = 0.25;
  /// [px/sigma] the least noise scale a frame is credited with: the keypoint detector's own
  /// resolution. ORB finds a keypoint on its pyramid level's pixel grid, and sigma = 1.2^octave
  /// is that level's pixel, so a residual carries the rounding of two positions, uniform over
  /// one sigma on each axis: 1/sqrt(6) sigma per axis. A frame can measure less only when its two
  /// roundings happen to agree (little image motion); that agreement does not hold for a region
  /// whose rounding falls the other way, and a neighbourhood's shared offset would then look
  /// significant against a scale no detector delivers. 0 for sub-pixel keypoints (or to measure
  /// s alone). >= 0.
  double min_scale = 0.4082482904638631;  // 1 / sqrt(6), rounded to double
};

/// Spatial coherence: a moving object's matches are neighbours (in the image and in depth) and
/// share a residual that departs from the background's. Per match i, c_i is the mean whitened,
/// centred residual of its neighbours (matches of the fit set in the 3 x 3 image cells around
/// it and, when depths are set, within `depth_ratio` squared in depth), each clamped to the
/// gate; c_i is shrunk towards 0 by its significance, c'_i = c_i max(0, 1 - z0 / z_i) with
/// z_i = |c_i| sqrt(N_i) / s, and the evidence is the log-likelihood ratio of "moves with its
/// neighbours" over "moves with the background" under the noise model:
/// l_i = (2 d_i . c'_i - |c'_i|^2) / (2 s^2).
struct CoherenceEvidence {
  bool enabled = true;
  double cell_px = 40.0;      ///< [px] side of a neighbourhood cell, > 0
  double depth_ratio = 1.15;  ///< depth layers are this ratio thick, > 1
  double z0 = 3.0;            ///< significance (in standard errors) below which c_i is noise
  double floor = 2.0;         ///< evidence counts only above this log-likelihood ratio, >= 0
  /// A flagged match (kept out of the fit under FlaggedPolicy::FitWithout) takes its consensus
  /// over every neighbour inside the gate, flagged ones included, so a group of flagged matches
  /// that moves together vouches for itself; an unflagged match's consensus stays over the fit
  /// set's neighbours alone. For callers whose flag means "new, not yet trusted" (a map point on
  /// probation). Off by default: where the flag means "on or near a mask", the mask's rim of
  /// static matches then takes the person's consensus (docs/screening.md).
  bool flagged_consensus = false;
};

/// The mask's neighbourhood: a match within `radius_px` of a dynamic-object mask whose
/// magnitude is above `min_scales` noise scales is likely an edge the mask missed.
struct MaskEvidence {
  bool enabled = true;
  double radius_px = 10.0;  ///< [px] > 0
  double min_scales = 4.0;  ///< > 0
};

/// Persistence: a track or map point the caller has seen screened out before (its outlier
/// history, Matches::set_outlier_history) counts as evidence above `floor`, once its magnitude
/// is above `min_scales` noise scales. Below one scale (the mode of the background's own
/// residuals, 2-D Gaussian noise of scale s) the residual fits the background better than a
/// typical static match does, and a prior alone must not overrule that: callers record the
/// screen's decisions into the history, so a static point rejected once would otherwise stay
/// rejected for as long as it is tracked.
struct HistoryEvidence {
  bool enabled = true;
  double floor = 0.5;       ///< in [0, 1)
  double min_scales = 1.0;  ///< >= 0; 0: the history fires at any magnitude
};

/// How the dominant residual field resists a dynamic object that holds many matches.
/// The model of the field refitted on the matches that look static (FieldFit::refit_model).
enum class RefitModel {
  Center,  ///< the screen's ResidualOptions::center model (affine by default)
  Rigid    ///< the pixel shift of a small rigid motion (rigid_field.hpp)
};

struct FieldFit {
  /// [px] each coarse image cell of this side weighs at most as much as the average occupied
  /// cell: a person crowding a few cells cannot outvote the background spread over the image.
  /// 0 = off.
  double balance_cell_px = 80.0;
  /// refit the field on the matches the evidence calls static (one extra pass)
  bool refit_on_static = true;
  /// the refit's window, in noise scales s: tight enough that a second population (a person a
  /// few noise levels off the background) cannot join the fit and tilt it. > 0.
  double refit_window_scales = 2.0;
  /// The refit's model: the residuals' `center` model, or a rigid field (rigid_field.hpp) fitted
  /// from the affine one. Rigid needs `camera` and the matches' depths (a match without one
  /// moves as a point at infinity). The SLAM example's trackers refit rigidly in the rounds
  /// after the first refinement (later_rounds_config).
  RefitModel refit_model = RefitModel::Center;
  /// [px] the intrinsics of the predicted pixels, for RefitModel::Rigid
  PinholeCamera<double> camera{};
};

/// The HBOS screen on reprojection residuals. Default-constructed = the recommended screen; see
/// the file comment for the reasons, `magnitude_only()` for the previous (single-feature)
/// default and `paper()` for the literal method.
///
/// With the noise gate on, a match is rejected when its magnitude is beyond the gate, or when,
/// inside it, evidence fires (coherence, mask neighbourhood, history above their floors) and
/// its HBOS score on the fired features — histograms fitted on the matches that look static —
/// is above the threshold. The reported score is max(t m / G, evidence score), so
/// score > threshold is the decision in every case.
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
  /// anyway, and it bounds the bin count (and so the memory) whatever the input. A clipped match
  /// is never fitted and always scores the histogram's cap.
  double magnitude_clip = 64.0;
  AngleFeature angle = AngleFeature::None;     ///< angle evidence
  FeatureSpec angle_spec = angle_feature(16);  ///< binning of the angle [rad]
  double angle_gate = 2.447;  ///< [px/sigma] AboveNoise: only residuals above this carry an angle
  ScoringOptions scoring{};   ///< empty-bin rule of the histograms
  /// The cut on the summed score. FixedThreshold{t} rejects bins whose density is below
  /// exp(-t) of the modal bin's.
  ThresholdRule threshold = FixedThreshold{1.5};
  /// [px/sigma] noise floor: a match whose (centered, whitened) magnitude is at most this is never
  /// rejected; 0 (the default) disables it. Only used with the noise gate off.
  double keep_below = 0.0;
  NoiseGate gate{};               ///< the noise-calibrated cut (off: the magnitude HBOS decides)
  CoherenceEvidence coherence{};  ///< needs the gate
  MaskEvidence mask{};            ///< needs the gate and mask distances in the matches
  HistoryEvidence history{};      ///< needs the gate and outlier histories in the matches
  FieldFit field{};               ///< robust fitting of the dominant residual field

  /// The previous default: the centred, whitened magnitude alone, fixed-width HBOS bins and a
  /// fixed score cut, no gate, no further evidence. For comparison (docs/screening.md).
  [[nodiscard]] static HbosScreen magnitude_only() {
    HbosScreen s;
    s.gate.enabled = false;
    s.coherence.enabled = false;
    s.mask.enabled = false;
    s.history.enabled = false;
    s.field.balance_cell_px = 0.0;
    s.field.refit_on_static = false;
    return s;
  }

  /// The paper's screen taken literally: raw pixel magnitude and raw angle, independent
  /// histograms of 10 equal-width bins over [min, max], two-sided, no centering, threshold
  /// eq. 6 `0.7 (max - min) + min`. For reproduction and comparison only (see docs/screening.md).
  [[nodiscard]] static HbosScreen paper() {
    HbosScreen s = magnitude_only();
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

/// Reject matches whose residual exceeds a fixed number of pixels. The score is |r|^2 [px^2]
/// against max_px^2 (the magnitude, |r| [px], against max_px), so that no match needs a square
/// root, as in ORB-SLAM2's chi^2 test.
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
  const NoiseGate& g = s.gate;
  require(std::isfinite(g.floor) && g.floor > 0.0, "NoiseGate floor must be finite and > 0, got ",
          g.floor);
  require(std::isfinite(g.scales) && g.scales > 0.0,
          "NoiseGate scales must be finite and > 0, got ", g.scales);
  require(g.scale_quantile > 0.0 && g.scale_quantile < 1.0,
          "NoiseGate scale_quantile must lie in (0, 1), got ", g.scale_quantile);
  require(std::isfinite(g.min_scale) && g.min_scale >= 0.0,
          "NoiseGate min_scale must be finite and >= 0, got ", g.min_scale);
  const CoherenceEvidence& c = s.coherence;
  require(std::isfinite(c.cell_px) && c.cell_px >= 1.0,
          "CoherenceEvidence cell_px must be finite and >= 1, got ", c.cell_px);
  require(std::isfinite(c.depth_ratio) && c.depth_ratio > 1.0 && c.depth_ratio <= 100.0,
          "CoherenceEvidence depth_ratio must lie in (1, 100], got ", c.depth_ratio);
  require(std::isfinite(c.z0) && c.z0 >= 0.0, "CoherenceEvidence z0 must be finite and >= 0, got ",
          c.z0);
  require(std::isfinite(c.floor) && c.floor >= 0.0,
          "CoherenceEvidence floor must be finite and >= 0, got ", c.floor);
  require(std::isfinite(s.mask.radius_px) && s.mask.radius_px > 0.0,
          "MaskEvidence radius_px must be finite and > 0, got ", s.mask.radius_px);
  require(std::isfinite(s.mask.min_scales) && s.mask.min_scales > 0.0,
          "MaskEvidence min_scales must be finite and > 0, got ", s.mask.min_scales);
  require(s.history.floor >= 0.0 && s.history.floor < 1.0,
          "HistoryEvidence floor must lie in [0, 1), got ", s.history.floor);
  require(std::isfinite(s.history.min_scales) && s.history.min_scales >= 0.0,
          "HistoryEvidence min_scales must be finite and >= 0, got ", s.history.min_scales);
  require(std::isfinite(s.field.balance_cell_px) &&
              (s.field.balance_cell_px == 0.0 || s.field.balance_cell_px >= 1.0),
          "FieldFit balance_cell_px must be 0 (off) or finite and >= 1, got ",
          s.field.balance_cell_px);
  require(std::isfinite(s.field.refit_window_scales) && s.field.refit_window_scales > 0.0,
          "FieldFit refit_window_scales must be finite and > 0, got ", s.field.refit_window_scales);
  if (s.field.refit_model == RefitModel::Rigid) {
    require(s.field.refit_on_static && s.residuals.center != ResidualCenter::None,
            "FieldFit refit_model Rigid refits the field on the matches that look static: it needs "
            "refit_on_static and a residuals.center other than None");
    validate(s.field.camera);
  }
  require(!s.gate.enabled || std::holds_alternative<FixedThreshold>(s.threshold),
          "HbosScreen's noise gate needs a FixedThreshold score cut");
  require(!s.gate.enabled || s.angle == AngleFeature::None,
          "HbosScreen's noise gate does not combine with an angle feature");
  require(!s.gate.enabled || s.residuals.whiten,
          "HbosScreen's noise gate works on whitened magnitudes: residuals.whiten must be true");
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
  // A stereo match's chi^2 is rescaled by this ratio onto the mono gate; bounded so that the
  // rescaling neither underflows nor overflows in float (any sane pair is near 0.77).
  const double ratio = g.chi2_mono / g.chi2_stereo;
  require(ratio >= 1e-6 && ratio <= 1e6,
          "ChiSquareGate chi2_mono / chi2_stereo must lie in [1e-6, 1e6], got ", g.chi2_mono, " / ",
          g.chi2_stereo);
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

/// How the screening rounds after the first (the rounds of a pose optimisation, after a
/// refinement on the survivors) differ from the first, for a strategy with a noise gate.
struct LaterRounds {
  /// [px/sigma] their noise gate's floor instead of the config's own; 0 = the config's own
  double gate_floor = 0.0;
  /// With intrinsics: the default screen refits its field as a rigid field (RefitModel::Rigid)
  /// with them. After a refinement, what an affine field still fits on real frames is mostly
  /// structure no pose error gives (docs/results.md, "A field only a camera motion can give").
  std::optional<PinholeCamera<double>> rigid_field;
};

/// The config of the screening rounds after the first, as `later` says; nullopt when nothing
/// would change: a strategy without a noise gate, or a gate floor of 0 (every round alike) or
/// the config's own and no rigid field (or a config that already refits rigidly with the same
/// intrinsics). One rule for every caller that writes the rounds loop (projection.hpp's helper,
/// the SLAM example's screening stage).
/// \throws InvalidArgument if the gate floor is negative or not finite, or the intrinsics are
/// not valid (PinholeCamera).
[[nodiscard]] inline std::optional<ScreenConfig> later_rounds_config(const ScreenConfig& config,
                                                                     const LaterRounds& later) {
  detail::require(std::isfinite(later.gate_floor) && later.gate_floor >= 0.0,
                  "the later rounds' gate floor must be finite and >= 0, got ", later.gate_floor);
  if (later.rigid_field) detail::validate(*later.rigid_field);
  const auto* gated = std::get_if<HbosScreen>(&config.strategy);
  if (gated == nullptr || !gated->gate.enabled) return std::nullopt;
  const bool new_floor = later.gate_floor != 0.0 && gated->gate.floor != later.gate_floor;
  // A screen without a field to refit has nothing to make rigid.
  const bool can_refit =
      gated->field.refit_on_static && gated->residuals.center != ResidualCenter::None;
  const bool new_field =
      later.rigid_field && can_refit &&
      !(gated->field.refit_model == RefitModel::Rigid && gated->field.camera == *later.rigid_field);
  if (!new_floor && !new_field) return std::nullopt;
  ScreenConfig result = config;
  HbosScreen& s = std::get<HbosScreen>(result.strategy);
  if (new_floor) s.gate.floor = later.gate_floor;
  if (new_field) {
    s.field.refit_model = RefitModel::Rigid;
    s.field.camera = *later.rigid_field;
  }
  return result;  // valid: `config` was, a floor > 0 and valid intrinsics keep it so
}

/// later_rounds_config with a gate floor alone.
[[nodiscard]] inline std::optional<ScreenConfig> later_rounds_config(const ScreenConfig& config,
                                                                     double later_gate_floor) {
  return later_rounds_config(config, LaterRounds{later_gate_floor, std::nullopt});
}

/// Short name of a strategy's family, for tables and logs.
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

/// One entry of the table of named strategies.
struct NamedStrategy {
  const char* name;         ///< what a command line or config file says
  const char* description;  ///< one line for --help and docs
  ScreenStrategy (*make)();
};

/// The one table of named strategies: every command, study and benchmark parses through it.
[[nodiscard]] inline const std::array<NamedStrategy, 7>& named_strategies() {
  static const std::array<NamedStrategy, 7> table = {{
      {"default", "HBOS screen: noise-calibrated gate + coherence, mask and history evidence",
       [] { return ScreenStrategy{HbosScreen{}}; }},
      {"paper", "the HBOS-SLAM paper taken literally (magnitude + angle, eq. 6)",
       [] { return ScreenStrategy{HbosScreen::paper()}; }},
      {"magnitude", "HBOS on the centred whitened magnitude alone (the previous default)",
       [] { return ScreenStrategy{HbosScreen::magnitude_only()}; }},
      {"chi2", "ORB-SLAM2's chi^2 gate (5.991, sigma = 1.2^octave)",
       [] { return ScreenStrategy{ChiSquareGate{}}; }},
      {"fixed", "a fixed 3 px gate", [] { return ScreenStrategy{FixedPixelGate{}}; }},
      {"quantile", "CFP-SLAM's 0.8 quantile of |r|", [] { return ScreenStrategy{QuantileGate{}}; }},
      {"mad", "median + 3 x 1.4826 MAD of |r|/sigma", [] { return ScreenStrategy{MadGate{}}; }},
  }};
  return table;
}

/// The strategy called `name` in named_strategies().
/// \throws InvalidArgument naming the value and the choices.
[[nodiscard]] inline ScreenStrategy parse_screen_strategy(std::string_view name) {
  std::string choices;
  for (const NamedStrategy& s : named_strategies()) {
    if (name == s.name) return s.make();
    choices += choices.empty() ? "" : ", ";
    choices += s.name;
  }
  throw InvalidArgument(detail::concat("screen strategy '", name, "' is not one of ", choices));
}

}  // namespace hbos
