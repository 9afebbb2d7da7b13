// libFuzzer target: the reprojection screen (hbos/screening.hpp) on fuzzed matches (pixels,
// sigmas, stereo coordinates, flags, depths, mask distances, histories) with fuzzed configs of
// every strategy. Each call returns a result or throws hbos::InvalidArgument; a screened frame
// has one finite score and one decision per match.

#include <hbos/screening.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "fuzz_check.hpp"
#include "fuzz_input.hpp"

namespace {

using hbos::fuzz::FuzzInput;

hbos::ScreenStrategy fuzz_strategy(FuzzInput& in) {
  switch (in.byte() % 8) {
    case 0:
      return hbos::FixedPixelGate{in.parameter(3.0)};
    case 1:
      return hbos::ChiSquareGate{in.parameter(5.991), in.parameter(7.815)};
    case 2:
      return hbos::QuantileGate{in.parameter(0.8), in.flag()};
    case 3:
      return hbos::MadGate{in.parameter(3.0), in.flag()};
    case 4:
      return hbos::HbosScreen::paper();
    case 5:
      return hbos::HbosScreen::magnitude_only();
    default:
      break;
  }
  hbos::HbosScreen s;
  if (in.flag()) s = hbos::HbosScreen::magnitude_only();
  s.residuals.whiten = in.flag();
  s.residuals.center = static_cast<hbos::ResidualCenter>(in.byte() % 3);
  if (in.flag()) s.residuals.center_window = in.parameter(3.0);
  if (in.flag()) s.residuals.center_iterations = static_cast<int>(in.byte()) - 8;
  if (in.flag()) {
    s.magnitude.binning.method = static_cast<hbos::BinningMethod>(in.byte() % 3);
    s.magnitude.binning.width = in.parameter(0.25);
    s.magnitude.binning.rule = static_cast<hbos::BinCountRule>(in.byte() % 6);
    s.magnitude.binning.bins = static_cast<Eigen::Index>(in.count(10));
    s.magnitude.binning.shifts = 1 + static_cast<Eigen::Index>(in.byte() % 4);
    s.magnitude.tail = static_cast<hbos::Tail>(in.byte() % 3);
  }
  if (in.flag()) s.magnitude_clip = in.parameter(64.0);
  s.angle = static_cast<hbos::AngleFeature>(in.byte() % 3);
  if (in.flag()) s.angle_gate = in.parameter(2.447);
  if (in.flag()) s.scoring.empty_bin_count = in.parameter(0.5);
  if (in.flag()) s.keep_below = in.parameter(1.0);
  if (in.flag()) {
    switch (in.byte() % 4) {
      case 0:
        s.threshold = hbos::AdaptiveRange{in.parameter(0.7)};
        break;
      case 1:
        s.threshold = hbos::Contamination{in.parameter(0.1)};
        break;
      case 2:
        s.threshold = hbos::MedianMad{in.parameter(3.0), in.flag()};
        break;
      default:
        s.threshold = hbos::FixedThreshold{in.parameter(1.5)};
        break;
    }
  }
  s.gate.enabled = in.flag();
  if (in.flag()) s.gate.floor = in.parameter(2.447);
  if (in.flag()) s.gate.scales = in.parameter(5.0);
  if (in.flag()) s.gate.scale_quantile = in.parameter(0.25);
  if (in.flag()) s.gate.min_scale = in.parameter(0.408);
  s.coherence.enabled = in.flag();
  if (in.flag()) s.coherence.cell_px = in.parameter(40.0);
  if (in.flag()) s.coherence.depth_ratio = in.parameter(1.15);
  s.mask.enabled = in.flag();
  if (in.flag()) s.mask.radius_px = in.parameter(10.0);
  s.history.enabled = in.flag();
  if (in.flag()) s.history.floor = in.parameter(0.5);
  if (in.flag()) s.field.balance_cell_px = in.parameter(80.0);
  s.field.refit_on_static = in.flag();
  // From two switches already drawn, so both paths are fuzzed and the seed corpus keeps the
  // meaning of every byte.
  s.coherence.flagged_consensus = s.mask.enabled != s.history.enabled;
  return s;
}

template <class Scalar>
Scalar as_scalar(double v) {
  if (std::isnan(v)) return std::numeric_limits<Scalar>::quiet_NaN();
  if (v > static_cast<double>(std::numeric_limits<Scalar>::max()))
    return std::numeric_limits<Scalar>::infinity();
  if (v < static_cast<double>(std::numeric_limits<Scalar>::lowest()))
    return -std::numeric_limits<Scalar>::infinity();
  return static_cast<Scalar>(v);
}

template <class Scalar>
void run(FuzzInput& in) {
  using V2 = Eigen::Matrix<Scalar, 2, 1>;
  hbos::ScreenConfig config;
  config.strategy = fuzz_strategy(in);
  config.flagged = static_cast<hbos::FlaggedPolicy>(in.byte() % 3);
  if (in.flag()) config.min_fit_matches = static_cast<Eigen::Index>(in.count(10));
  hbos::Matches<Scalar> matches;
  const std::size_t n = in.below(40);
  // Mostly pixels near a common residual (a static background), some anywhere.
  const double shift_x = (static_cast<double>(in.byte()) - 128.0) / 32.0;
  const double shift_y = (static_cast<double>(in.byte()) - 128.0) / 32.0;
  try {
    for (std::size_t i = 0; i < n; ++i) {
      const bool wild = in.byte() % 4 == 0;
      const double px = static_cast<double>(in.byte()) * 2.5;
      const double py = static_cast<double>(in.byte()) * 1.9;
      const V2 predicted(as_scalar<Scalar>(wild ? in.value() : px),
                         as_scalar<Scalar>(wild ? in.value() : py));
      const V2 observed(as_scalar<Scalar>(px + shift_x + (wild ? in.value() : 0.0)),
                        as_scalar<Scalar>(py + shift_y));
      const Scalar sigma = as_scalar<Scalar>(in.flag() ? 1.0 : in.parameter(1.2));
      const bool flag = in.byte() % 5 == 0;
      if (in.byte() % 4 == 0) {
        matches.add_stereo(predicted, observed, as_scalar<Scalar>(px - 10.0),
                           as_scalar<Scalar>(in.flag() ? px - 10.0 : in.value()), sigma, flag);
      } else {
        matches.add(predicted, observed, sigma, flag);
      }
      const auto last = static_cast<Eigen::Index>(matches.size() - 1);
      if (in.byte() % 3 == 0) matches.set_depth(last, as_scalar<Scalar>(in.parameter(2.0)));
      if (in.byte() % 3 == 0) matches.set_mask_distance(last, as_scalar<Scalar>(in.value()));
      if (in.byte() % 3 == 0) matches.set_outlier_history(last, as_scalar<Scalar>(in.value()));
    }
  } catch (const hbos::InvalidArgument&) {
    // a rejected match: screen what was added
  }
  try {
    hbos::ReprojectionScreen<Scalar> screen(config);
    // Finding of the campaign (docs/fuzzing.md): reserve(2^46) passed `n >= 1` and died in
    // operator new; reserve now refuses n beyond 2^31. Counts between 2^20 and 2^31 are legal
    // but reserve gigabytes, so only counts up to 2^20 are passed here.
    if (in.flag()) {
      const long long n_reserve = in.count(16);
      if (n_reserve <= (1LL << 20)) screen.reserve(static_cast<Eigen::Index>(n_reserve));
    }
    const auto& r = screen.screen(matches);
    check(r.size() == matches.size());
    for (Eigen::Index i = 0; i < r.size(); ++i) check(!std::isnan(r.score(i)));
    // A second frame through the same object reuses its buffers.
    const auto& again = screen.screen(matches);
    check(again.size() == matches.size());
  } catch (const hbos::InvalidArgument&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput in(data, size);
  if (in.flag()) {
    run<double>(in);
  } else {
    run<float>(in);
  }
  return 0;
}
