#include "frontend/residual_screen.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>
#include <hbos/screening/matches.hpp>
#include <hbos/screening/screen.hpp>
#include <hbos/screening/strategies.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <variant>

namespace hbos::slam {

namespace {

using Clock = std::chrono::steady_clock;

double microseconds_since(Clock::time_point start) {
  return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}

// The value of an optional evidence column for match i; NaN when the column is absent.
double value_or_nan(const std::vector<double>& column, std::size_t i) {
  return i < column.size() ? column[i] : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

void keep_out_provisional(const std::vector<std::uint8_t>& provisional, int min_survivors,
                          std::vector<std::uint8_t>& use) {
  if (provisional.empty()) return;
  int proven = 0;
  for (std::size_t i = 0; i < use.size(); ++i)
    proven += (use[i] != 0 && (i >= provisional.size() || provisional[i] == 0)) ? 1 : 0;
  if (proven < min_survivors) return;
  for (std::size_t i = 0; i < use.size() && i < provisional.size(); ++i) {
    if (provisional[i] != 0) use[i] = 0;
  }
}

const std::vector<std::string>& screen_strategy_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    for (const hbos::NamedStrategy& s : hbos::named_strategies()) list.emplace_back(s.name);
    list.emplace_back("none");
    return list;
  }();
  return names;
}

struct ResidualScreen::Impl {
  std::optional<hbos::ReprojectionScreend> screen;  // empty for "none"
  hbos::Matches<double> matches;                    // reused every frame
  std::vector<std::size_t> match_of;                // hbos match k -> caller's match index
  std::vector<std::uint8_t> use;                    // refinement mask, caller's indices
  hbos::ScreenConfig first;                         // the config of the first round
  std::optional<hbos::ScreenConfig> later;          // of the later ones, where they differ
  // The intrinsics `later` refits its rigid field with (ScreenStageConfig::
  // later_rounds_rigid_field): the refiner's camera, known from the first frame on.
  std::optional<hbos::PinholeCamerad> rigid_camera;
};

ResidualScreen::ResidualScreen(const ScreenStageConfig& config)
    : config_(config), impl_(std::make_unique<Impl>()) {
  if (config_.rounds < 1 || config_.min_inliers < 3) {
    throw InvalidArgument(
        fmt::format("screen settings: rounds {} must be >= 1, min inliers {} >= 3", config_.rounds,
                    config_.min_inliers));
  }
  if (config_.screen) {
    // This stage flags only points on probation (below), so their consensus among themselves
    // is what flagged_consensus measures; the library's default leaves it off, where a flag can
    // also mean "near a mask".
    hbos::ScreenConfig screen = *config_.screen;
    if (auto* s = std::get_if<hbos::HbosScreen>(&screen.strategy))
      s->coherence.flagged_consensus =
          s->coherence.flagged_consensus || config_.provisional_consensus;
    impl_->screen.emplace(screen);  // validates
    impl_->first = screen;
    // After a refinement on the survivors, the noise gate may close below chi^2's gate (see
    // ScreenStageConfig::later_rounds_gate_floor; unset: every round alike, a tracker passes
    // its own value). Throws for a negative or non-finite floor.
    impl_->later = hbos::later_rounds_config(screen, config_.later_rounds_gate_floor.value_or(0.0));
  }
}

ResidualScreen::~ResidualScreen() = default;
ResidualScreen::ResidualScreen(ResidualScreen&&) noexcept = default;
ResidualScreen& ResidualScreen::operator=(ResidualScreen&&) noexcept = default;

ScreenOutcome ResidualScreen::screen(const std::vector<Eigen::Vector3d>& points_prev,
                                     const std::vector<Eigen::Vector2d>& observed,
                                     const std::vector<double>& sigma,
                                     Eigen::Isometry3d& T_cur_prev, const PoseRefiner& refiner,
                                     const MatchEvidence& evidence) {
  const std::size_t n = points_prev.size();
  const hbos::PinholeCamerad& camera = refiner.camera();
  if (impl_->screen && config_.later_rounds_rigid_field.value_or(false) &&
      impl_->rigid_camera != camera) {
    impl_->later = hbos::later_rounds_config(
        impl_->first, hbos::LaterRounds{config_.later_rounds_gate_floor.value_or(0.0), camera});
    impl_->rigid_camera = camera;
  }
  ScreenOutcome out;
  out.inlier.assign(n, 0);
  out.magnitude.assign(n, std::numeric_limits<double>::quiet_NaN());
  out.score.assign(n, std::numeric_limits<double>::quiet_NaN());

  if (!impl_->screen) {
    // No screen: every match is kept (the tracker then refines the pose on all of them).
    out.inlier.assign(n, 1);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d p = T_cur_prev * points_prev[i];
      if (p.z() > 0.0) out.magnitude[i] = (camera.project(p) - observed[i]).norm();
    }
    out.statistic = "residual_px";
    out.unit = "px";
    return out;
  }

  // 1. The predictions under the rough pose, with the evidence the caller has; a point behind
  // the camera cannot be screened.
  hbos::Matches<double>& matches = impl_->matches;
  matches.clear();
  impl_->match_of.clear();
  // Provisional matches are passed as flagged only where that keeps them out of the fit and
  // nothing more (another policy would reject them or ignore the flag).
  const bool flag_provisional = config_.screen->flagged == hbos::FlaggedPolicy::FitWithout;
  const auto provisional = [&](std::size_t i) {
    return i < evidence.provisional.size() && evidence.provisional[i] != 0;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p = T_cur_prev * points_prev[i];
    if (!(p.z() > 0.0)) continue;
    const auto k = matches.size();
    matches.add(camera.project(p), observed[i], sigma[i], flag_provisional && provisional(i));
    matches.set_depth(k, p.z());
    const double mask_distance = value_or_nan(evidence.mask_distance_px, i);
    if (!std::isnan(mask_distance)) matches.set_mask_distance(k, mask_distance);
    const double history = value_or_nan(evidence.outlier_history, i);
    if (!std::isnan(history)) matches.set_outlier_history(k, std::clamp(history, 0.0, 1.0));
    impl_->match_of.push_back(i);
  }
  if (matches.size() == 0) return out;

  // 2. ORB-SLAM2's rounds, as PoseOptimization runs them: screen -> refine the pose on the
  // survivors -> re-project -> re-screen. Every round screens all matches again.
  std::vector<std::uint8_t>& use = impl_->use;
  double refine_us = 0.0, screen_us = 0.0;
  const hbos::ScreenResult<double>* result = nullptr;
  for (int round = 1;; ++round) {
    if (impl_->later) impl_->screen->set_config(round == 1 ? impl_->first : *impl_->later);
    const auto start = Clock::now();
    result = &impl_->screen->screen(matches);
    screen_us += microseconds_since(start);
    out.rounds = round;
    if (round == config_.rounds || result->n_inliers() < config_.min_inliers) break;
    const auto refine_start = Clock::now();
    use.assign(n, 0);
    for (Eigen::Index k = 0; k < matches.size(); ++k)
      use[impl_->match_of[static_cast<std::size_t>(k)]] = result->inlier(k) ? 1 : 0;
    keep_out_provisional(evidence.provisional, static_cast<int>(config_.min_inliers), use);
    refiner.refine(points_prev, observed, sigma, use, T_cur_prev);
    for (Eigen::Index k = 0; k < matches.size(); ++k) {
      const Eigen::Vector3d p =
          T_cur_prev * points_prev[impl_->match_of[static_cast<std::size_t>(k)]];
      // A point pushed behind the camera keeps its old prediction (and will be judged on it).
      if (p.z() > 0.0) {
        matches.set_predicted(k, camera.project(p));
        matches.set_depth(k, p.z());
      }
    }
    refine_us += microseconds_since(refine_start);
  }

  // 3. Back to the caller's indices.
  for (Eigen::Index k = 0; k < matches.size(); ++k) {
    const std::size_t i = impl_->match_of[static_cast<std::size_t>(k)];
    out.inlier[i] = result->inlier(k) ? 1 : 0;
    out.magnitude[i] = result->magnitude(k);
    out.score[i] = result->score(k);
  }
  out.threshold = result->threshold();
  out.magnitude_cut = result->magnitude_cut();
  out.statistic = result->n_features() > 1 ? "magnitude (+ evidence)" : result->feature_name(0);
  out.unit = result->magnitude_unit();
  out.score_unit = result->unit();
  out.refine_us = refine_us;
  out.screen_us = screen_us;
  return out;
}

}  // namespace hbos::slam
