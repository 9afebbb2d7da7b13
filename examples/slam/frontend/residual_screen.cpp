#include "frontend/residual_screen.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>
#include <hbos/screening/residual_field.hpp>
#include <hbos/screening/screen.hpp>
#include <hbos/screening/strategies.hpp>

#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace hbos::slam {

namespace {

using Clock = std::chrono::steady_clock;

double microseconds_since(Clock::time_point start) {
  return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}

// The strategy behind each name; nullopt for "none".
std::optional<hbos::ScreenStrategy> strategy_for(const std::string& name) {
  if (name == "default") return hbos::HbosScreen{};
  if (name == "paper") return hbos::HbosScreen::paper();
  if (name == "chi2") return hbos::ChiSquareGate{};
  if (name == "fixed") return hbos::FixedPixelGate{};
  if (name == "quantile") return hbos::QuantileGate{};
  if (name == "mad") return hbos::MadGate{};
  if (name == "none") return std::nullopt;
  throw InvalidArgument(fmt::format(
      "screen '{}' is not one of default, paper, chi2, fixed, quantile, mad, none", name));
}

// The screen's threshold in the units of its magnitude, where the strategy is a gate on it.
double magnitude_cut(const hbos::ScreenStrategy& strategy, double threshold) {
  if (std::holds_alternative<hbos::ChiSquareGate>(strategy)) return std::sqrt(threshold);
  if (std::holds_alternative<hbos::HbosScreen>(strategy)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return threshold;  // fixed, quantile and MAD gates score the magnitude itself
}

bool whitened(const hbos::ScreenStrategy& strategy) {
  if (const auto* h = std::get_if<hbos::HbosScreen>(&strategy)) return h->residuals.whiten;
  if (const auto* q = std::get_if<hbos::QuantileGate>(&strategy)) return q->whiten;
  if (const auto* m = std::get_if<hbos::MadGate>(&strategy)) return m->whiten;
  return std::holds_alternative<hbos::ChiSquareGate>(strategy);
}

}  // namespace

const std::vector<std::string>& screen_strategy_names() {
  static const std::vector<std::string> names = {"default",  "paper", "chi2", "fixed",
                                                 "quantile", "mad",   "none"};
  return names;
}

struct ResidualScreen::Impl {
  std::optional<hbos::ReprojectionScreend> screen;  // empty for "none"
  hbos::Matches<double> matches;                    // reused every frame
  std::vector<std::size_t> match_of;                // hbos match k -> caller's match index
};

ResidualScreen::ResidualScreen(const ScreenStageConfig& config)
    : config_(config), impl_(std::make_unique<Impl>()) {
  if (config_.rounds < 1 || config_.min_inliers < 3) {
    throw InvalidArgument(
        fmt::format("screen settings: rounds {} must be >= 1, min inliers {} >= 3", config_.rounds,
                    config_.min_inliers));
  }
  if (auto strategy = strategy_for(config_.strategy)) impl_->screen.emplace(std::move(*strategy));
}

ResidualScreen::~ResidualScreen() = default;
ResidualScreen::ResidualScreen(ResidualScreen&&) noexcept = default;
ResidualScreen& ResidualScreen::operator=(ResidualScreen&&) noexcept = default;

ScreenOutcome ResidualScreen::screen(const std::vector<Eigen::Vector3d>& points_prev,
                                     const std::vector<Eigen::Vector2d>& observed,
                                     const std::vector<double>& sigma,
                                     Eigen::Isometry3d& T_cur_prev, const PoseRefiner& refiner) {
  const std::size_t n = points_prev.size();
  const hbos::PinholeCamerad& camera = refiner.camera();
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
    out.threshold = out.magnitude_cut = std::numeric_limits<double>::quiet_NaN();
    return out;
  }

  // 1. The predictions under the rough pose; a point behind the camera cannot be screened.
  hbos::Matches<double>& matches = impl_->matches;
  matches.clear();
  impl_->match_of.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p = T_cur_prev * points_prev[i];
    if (!(p.z() > 0.0)) continue;
    matches.add(camera.project(p), observed[i], sigma[i]);
    impl_->match_of.push_back(i);
  }
  if (matches.size() == 0) return out;

  // 2. Screen -> refine on the survivors -> re-project -> re-screen, config_.rounds screenings.
  std::vector<std::uint8_t> use(n, 0);
  double refine_us = 0.0;
  auto refit = [&](const hbos::ScreenResult<double>& result, hbos::Matches<double>& m) {
    if (result.n_inliers() < config_.min_inliers) return false;
    const auto start = Clock::now();
    std::fill(use.begin(), use.end(), std::uint8_t{0});
    for (Eigen::Index k = 0; k < m.size(); ++k) {
      use[impl_->match_of[static_cast<std::size_t>(k)]] = result.inlier(k) ? 1 : 0;
    }
    refiner.refine(points_prev, observed, sigma, use, T_cur_prev);
    for (Eigen::Index k = 0; k < m.size(); ++k) {
      const Eigen::Vector3d p =
          T_cur_prev * points_prev[impl_->match_of[static_cast<std::size_t>(k)]];
      // A point pushed behind the camera keeps its old prediction (and will be judged on it).
      if (p.z() > 0.0) m.set_predicted(k, camera.project(p));
    }
    refine_us += microseconds_since(start);
    return true;
  };
  const auto start = Clock::now();
  const hbos::ScreenResult<double>& result =
      impl_->screen->screen_iterated(matches, refit, config_.rounds);
  const double total_us = microseconds_since(start);

  // 3. Back to the caller's indices.
  for (Eigen::Index k = 0; k < matches.size(); ++k) {
    const std::size_t i = impl_->match_of[static_cast<std::size_t>(k)];
    out.inlier[i] = result.inlier(k) ? 1 : 0;
    out.magnitude[i] = result.magnitude(k);
    out.score[i] = result.score(k);
  }
  const hbos::ScreenStrategy& strategy = impl_->screen->config().strategy;
  out.threshold = result.threshold();
  out.magnitude_cut = magnitude_cut(strategy, out.threshold);
  out.statistic =
      result.n_features() > 1 ? "magnitude (angle also scored)" : result.feature_name(0);
  // chi^2 scores |r|^2 / sigma^2; the magnitude shown is its square root.
  if (std::holds_alternative<hbos::ChiSquareGate>(strategy)) {
    out.statistic = "residual_whitened (chi2 gate on its square)";
  }
  out.unit = whitened(strategy) ? "px/sigma" : "px";
  out.rounds = result.rounds();
  out.refine_us = refine_us;
  out.screen_us = total_us - refine_us;
  return out;
}

}  // namespace hbos::slam
