// Screen v2 (issue 7): the noise-calibrated gate, the evidence beyond one magnitude, the robust
// residual field, one round per call with its unit and cut, the strategy name table, and the
// clipped-magnitude defect. Synthetic matches here test properties; the claims about real data
// are tested on the labelled real residual cases (test_screen_real_cases.cpp).

#include <catch2/catch.hpp>

#include <hbos/screening.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "../support/screening_eval.hpp"

namespace {

using Vec2 = Eigen::Vector2d;

/// n static matches spread over a 640 x 480 image, whitened noise of scale `s` per axis,
/// depth 2 m, sigma 1.
hbos::Matchesd static_matches(int n, double s, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, s);
  std::uniform_real_distribution<double> x(0.0, 640.0), y(0.0, 480.0);
  hbos::Matchesd m;
  for (int i = 0; i < n; ++i) {
    const Vec2 p(x(rng), y(rng));
    m.add(p, p + Vec2(noise(rng), noise(rng)));
    m.set_depth(m.size() - 1, 2.0);
  }
  return m;
}

/// Adds `n` matches of an object in the box [x0, x0 + w] x [y0, y0 + h] whose residual is
/// `offset` plus the same noise, at depth `depth`, `flagged` or not.
void add_object(hbos::Matchesd& m, int n, const Vec2& offset, double s, double x0, double y0,
                double w, double h, double depth, std::uint32_t seed, bool flagged = false) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, s);
  std::uniform_real_distribution<double> x(x0, x0 + w), y(y0, y0 + h);
  for (int i = 0; i < n; ++i) {
    const Vec2 p(x(rng), y(rng));
    m.add(p, p + offset + Vec2(noise(rng), noise(rng)), 1.0, flagged);
    m.set_depth(m.size() - 1, depth);
  }
}

/// The default screen measuring the frame's noise scale alone, without the detector's floor
/// (NoiseGate::min_scale = 0): the screen before stop 25.
hbos::HbosScreen without_detector_floor() {
  hbos::HbosScreen s;
  s.gate.min_scale = 0.0;
  return s;
}

using hbos_test::rejected_share;

}  // namespace

TEST_CASE("defect: a crowd of gross mismatches at magnitude_clip is rejected, not kept",
          "[screen_v2][defect]") {
  // 150 good matches and 81 gross mismatches far beyond the clip: before the fix the clipped
  // bin was the modal bin, every score was 0 and all 81 were kept.
  hbos::Matchesd m = static_matches(150, 0.5, 7);
  for (int i = 0; i < 81; ++i) {
    const Vec2 p(10.0 + 7.0 * i, 240.0);
    m.add(p, p + Vec2(150.0 + i, -90.0));
  }
  for (const hbos::HbosScreen& s : {hbos::HbosScreen::magnitude_only(), hbos::HbosScreen{}}) {
    hbos::ReprojectionScreend screen(s);
    const auto& r = screen.screen(m);
    CHECK(rejected_share(r, 150, 231) == 1.0);
    // magnitude_only's known cost on pure noise is ~8 % (docs/screening.md); the gate's ~0.
    CHECK(rejected_share(r, 0, 150) < (s.gate.enabled ? 0.02 : 0.12));
  }
  SECTION("every fitted match clipped: all rejected, scores finite") {
    // Gross in scattered directions (identical residuals would be a rough-pose shift the field
    // absorbs, not mismatches).
    hbos::Matchesd gross;
    for (int i = 0; i < 20; ++i) {
      const double a = 2.399963 * i;
      gross.add(Vec2(20.0 * i, 15.0 * i),
                Vec2(20.0 * i, 15.0 * i) + 500.0 * Vec2(std::cos(a), std::sin(a)));
    }
    hbos::ReprojectionScreend screen(hbos::HbosScreen::magnitude_only());
    const auto& r = screen.screen(gross);
    CHECK(r.n_inliers() == 0);
    CHECK(r.scores().allFinite());
  }
}

TEST_CASE("defect: fired matches are charged by the static matches' magnitude histogram",
          "[screen_v2][defect]") {
  // Found by hbos-dynbench (walking_xyz, seed 1, no mask): the magnitude histogram was fitted on
  // a buffer the evidence histograms had already overwritten with their own values, so fired
  // matches were charged against the statics' coherence instead of their magnitudes. On a
  // rendered frame's tiny noise (s ~ 0.005 px/sigma) a static match beside a coherent object
  // has a coherence of -3e4, and that fit needed 1.3e5 bins and threw.
  hbos::Matchesd m = static_matches(600, 0.005, 11);
  const Eigen::Index n_static = m.size();
  add_object(m, 40, Vec2(2.2, 0.0), 0.005, 420.0, 300.0, 100.0, 100.0, 2.0, 13);  // inside the gate
  hbos::ReprojectionScreend screen(hbos::HbosScreen{});
  const hbos::ScreenResult<double>* r = nullptr;
  REQUIRE_NOTHROW(r = &screen.screen(m));
  CHECK(r->scores().allFinite());
  CHECK(rejected_share(*r, n_static, m.size()) == 1.0);
  CHECK(rejected_share(*r, 0, n_static) < 0.05);
  CHECK(r->n_rejected_by_evidence() == 40);
  // Every match charged on evidence: its magnitude's contribution is what a histogram of the
  // matches that look static (kept, nothing fired: every contribution 0) gives its magnitude.
  std::vector<double> static_magnitudes;
  const auto c = r->contributions();
  for (Eigen::Index i = 0; i < m.size(); ++i)
    if (r->inlier(i) && (c.row(i).array() == 0.0).all() && r->magnitude(i) <= r->magnitude_cut())
      static_magnitudes.push_back(r->magnitude(i));
  REQUIRE(static_magnitudes.size() > 500);
  hbos::Histogram<double> reference;
  std::vector<double> scratch;
  const Eigen::Map<const Eigen::VectorXd> column(
      static_magnitudes.data(), static_cast<Eigen::Index>(static_magnitudes.size()));
  reference.refit(column, hbos::HbosScreen{}.magnitude, hbos::ScoringOptions{}, scratch);
  Eigen::Index charged = 0;
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    if ((c.row(i).tail(3).array() == 0.0).all()) continue;
    ++charged;
    CHECK(c(i, 0) == reference.contribution(r->magnitude(i)));
  }
  CHECK(charged > 0);
}

TEST_CASE("the noise gate follows the frame's noise and never closes below chi^2's gate",
          "[screen_v2][gate][property]") {
  const double detector = 1.0 / std::sqrt(6.0);  // NoiseGate::min_scale's default
  CHECK(hbos::HbosScreen{}.gate.min_scale == detector);
  for (const double s : {0.1, 0.3, 0.5, 1.0, 2.0, 4.0}) {
    CAPTURE(s);
    const hbos::Matchesd m = static_matches(800, s, 11);
    hbos::ReprojectionScreend unfloored(without_detector_floor());
    CHECK(unfloored.screen(m).noise_scale() == Approx(s).epsilon(0.15));
    hbos::ReprojectionScreend screen;
    const auto& r = screen.screen(m);
    CHECK(std::string(r.magnitude_unit()) == "px/sigma");
    CHECK(r.noise_scale() >= detector);
    CHECK(r.noise_scale() == Approx(std::max(s, detector)).epsilon(0.15));
    CHECK(r.magnitude_cut() == Approx(std::max(2.447, 3.0 * r.noise_scale())));
    // Pure Gaussian noise: the gate alone drops the Rayleigh tail beyond max(2.447 / s, 3)
    // scales, at most exp(-4.5) = 1.1 %; evidence must not add much to it.
    CHECK(rejected_share(r, 0, m.size()) <= 0.02);
  }
}

TEST_CASE(
    "coherence: a group moving together inside the gate is rejected, the same "
    "magnitudes in random directions are not",
    "[screen_v2][coherence]") {
  const double s = 0.4;
  hbos::Matchesd m = static_matches(400, s, 3);
  const Eigen::Index first = m.size();
  // 1.6 px/sigma: inside chi^2's 2.447 gate, so no magnitude gate can see it.
  add_object(m, 80, Vec2(1.6, 0.3), s, 400.0, 150.0, 120.0, 200.0, 0.9, 4);
  hbos::ReprojectionScreend screen;
  const auto& r = screen.screen(m);
  CHECK(rejected_share(r, first, m.size()) > 0.8);
  CHECK(rejected_share(r, 0, first) < 0.02);
  CHECK(r.n_rejected_by_evidence() > 0);

  hbos::ReprojectionScreend chi2(hbos::ChiSquareGate{});
  CHECK(rejected_share(chi2.screen(m), first, m.size()) < 0.2);  // what chi^2 cannot do

  SECTION("scattered: the same magnitudes with random directions stay") {
    hbos::Matchesd scattered = static_matches(400, s, 3);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> angle(-M_PI, M_PI), x(0, 640), y(0, 480);
    for (int i = 0; i < 80; ++i) {
      const double a = angle(rng);
      const Vec2 p(x(rng), y(rng));
      scattered.add(p, p + 1.62 * Vec2(std::cos(a), std::sin(a)));
      scattered.set_depth(scattered.size() - 1, 2.0);
    }
    const auto& rs = screen.screen(scattered);
    CHECK(rejected_share(rs, first, scattered.size()) < 0.1);
  }
}

TEST_CASE(
    "coherence: a band a third of a sigma off is not called moving when the frame's keypoint "
    "roundings agreed, and a group moving 1.5 sigma still is",
    "[screen_v2][coherence][gate]") {
  // Rendered frames with little image motion: the two frames round most keypoints alike, so the
  // measured noise scale falls far below what a pixel-grid detector delivers (0.1 here against
  // 1/sqrt(6)); a band of the image whose rounding went the other way shares a third of a sigma
  // (docs/results.md, stop 25: such frames held 977 of 979 coherence rejections of one rendered
  // run). Measured against 0.1, that band is dozens of standard errors off; against the
  // detector's scale it is noise.
  const double agreed = 0.1;
  hbos::Matchesd m = static_matches(600, agreed, 31);
  const Eigen::Index band = m.size();
  add_object(m, 150, Vec2(-0.33, -0.12), agreed, 0.0, 260.0, 640.0, 70.0, 2.8, 32);
  const Eigen::Index moving = m.size();
  add_object(m, 60, Vec2(1.5, 0.2), agreed, 420.0, 80.0, 100.0, 140.0, 1.2, 33);

  hbos::ReprojectionScreend screen;
  const auto& r = screen.screen(m);
  CHECK(r.noise_scale() == Approx(1.0 / std::sqrt(6.0)));
  CHECK(rejected_share(r, band, moving) < 0.02);
  CHECK(rejected_share(r, 0, band) < 0.02);
  CHECK(rejected_share(r, moving, m.size()) > 0.9);

  // Without the detector's scale (the screen before stop 25) the band is called moving.
  hbos::ReprojectionScreend unfloored(without_detector_floor());
  const auto& u = unfloored.screen(m);
  CHECK(u.noise_scale() < 0.15);
  CHECK(rejected_share(u, band, moving) > 0.3);
}

TEST_CASE("a person holding 43 % of the matches in a corner cannot pull the residual field",
          "[screen_v2][field]") {
  // (At 60 % the field stays on the background but the noise scale inflates and the person is
  // kept: docs/screening.md, where the default does not win.)
  const double s = 0.5;
  hbos::Matchesd m = static_matches(200, s, 21);
  const Eigen::Index first = m.size();
  add_object(m, 150, Vec2(4.0, 1.0), s, 380.0, 100.0, 200.0, 300.0, 1.0, 22);
  hbos::ReprojectionScreend screen;
  const auto& r = screen.screen(m);
  CHECK(r.field().at(Vec2(100, 100)).norm() < 0.5);
  CHECK(rejected_share(r, 0, first) < 0.03);
  CHECK(rejected_share(r, first, m.size()) > 0.95);
}

TEST_CASE("mask neighbourhood and history are evidence only above their floors",
          "[screen_v2][evidence]") {
  const double s = 0.4;
  hbos::Matchesd m = static_matches(300, s, 31);
  // Two matches 2.2 px/sigma off (about 5.5 noise scales: beyond the mask floor of 4, inside
  // the gate of 2.447), one next to a mask, one far from it; two matches 1.5 px/sigma off (beyond
  // the history's floor of one scale, inside the gate) with a long and a short history; one match
  // as close as the background's noise with a long history.
  const Eigen::Index near_mask = m.size();
  m.add(Vec2(100, 100), Vec2(102.2, 100));
  m.set_mask_distance(near_mask, 3.0);
  const Eigen::Index far_mask = m.size();
  m.add(Vec2(500, 400), Vec2(502.2, 400));
  m.set_mask_distance(far_mask, 60.0);
  const Eigen::Index persistent = m.size();
  m.add(Vec2(300, 300), Vec2(301.5, 300.3));
  m.set_outlier_history(persistent, 0.9);
  const Eigen::Index forgiven = m.size();
  m.add(Vec2(320, 300), Vec2(321.5, 300.3));
  m.set_outlier_history(forgiven, 0.2);
  const Eigen::Index looks_static = m.size();
  m.add(Vec2(340, 300), Vec2(340.2, 300.1));
  m.set_outlier_history(looks_static, 0.9);
  hbos::ReprojectionScreend screen;
  const auto& r = screen.screen(m);
  // The premises: both mask matches inside the gate and beyond the mask floor, the history
  // matches beyond one noise scale, the last one below it.
  REQUIRE(r.magnitude_cut() == Approx(2.447).margin(1e-3));
  REQUIRE(r.magnitude(near_mask) < r.magnitude_cut());
  REQUIRE(r.magnitude(near_mask) > 4.0 * r.noise_scale());
  REQUIRE(r.magnitude(persistent) > r.noise_scale());
  REQUIRE(r.magnitude(looks_static) < r.noise_scale());
  CHECK_FALSE(r.inlier(near_mask));
  CHECK(r.inlier(far_mask));
  CHECK_FALSE(r.inlier(persistent));
  CHECK(r.inlier(forgiven));
  CHECK(r.inlier(looks_static));
  CHECK(r.score(near_mask) > r.threshold());
  CHECK(r.contributions()(near_mask, 2) > 0.0);  // charged to the "mask" feature
  CHECK(std::string(r.feature_name(2)) == "mask");
  CHECK(std::string(r.feature_name(3)) == "history");
}

TEST_CASE("a history charges a match only beyond its floor of noise scales",
          "[screen_v2][evidence][property]") {
  // Static frames where every match carries a long outlier history, as a static track would
  // after one wrong rejection. At any floor, a charged match lies beyond it; with the default
  // floor (one scale) far fewer are rejected than without it.
  std::mt19937 rng(57);
  std::uniform_real_distribution<double> share(0.6, 1.0);
  for (const double min_scales : {0.0, 1.0, 2.0, 3.0}) {
    hbos::HbosScreen settings;
    settings.history.min_scales = min_scales;
    hbos::ReprojectionScreend screen(settings);
    double kept = 0.0, total = 0.0;
    for (std::uint32_t seed = 0; seed < 10; ++seed) {
      hbos::Matchesd m = static_matches(400, 0.3 + 0.05 * seed, 200 + seed);
      for (Eigen::Index i = 0; i < m.size(); ++i) m.set_outlier_history(i, share(rng));
      const auto& r = screen.screen(m);
      for (Eigen::Index i = 0; i < r.size(); ++i) {
        if (r.contributions()(i, 3) > 0.0) CHECK(r.magnitude(i) > min_scales * r.noise_scale());
        kept += r.inlier(i) ? 1.0 : 0.0;
        total += 1.0;
      }
    }
    if (min_scales == 0.0) CHECK(kept / total < 0.5);
    if (min_scales == 1.0) CHECK(kept / total > 0.5);
  }
}

TEST_CASE("one round per call: the result says its unit and its cut", "[screen_v2][api]") {
  const hbos::Matchesd m = static_matches(200, 0.5, 41);
  struct Expect {
    hbos::ScreenStrategy strategy;
    const char* unit;
    const char* magnitude_unit;
  };
  for (const Expect& e :
       {Expect{hbos::ChiSquareGate{}, "px^2/sigma^2", "px/sigma"},
        Expect{hbos::FixedPixelGate{}, "px^2", "px"}, Expect{hbos::QuantileGate{}, "px", "px"},
        Expect{hbos::MadGate{}, "px/sigma", "px/sigma"},
        Expect{hbos::HbosScreen{}, "score", "px/sigma"},
        Expect{hbos::HbosScreen::paper(), "score", "px"}}) {
    hbos::ReprojectionScreend screen(e.strategy);
    const auto& r = screen.screen(m);
    CHECK(std::string(r.unit()) == e.unit);
    CHECK(std::string(r.magnitude_unit()) == e.magnitude_unit);
    for (Eigen::Index i = 0; i < r.size(); ++i) CHECK(r.inlier(i) == (r.score(i) <= r.threshold()));
  }
  hbos::ReprojectionScreend chi2(hbos::ChiSquareGate{});
  CHECK(chi2.screen(m).magnitude_cut() == Approx(std::sqrt(5.991)));
  hbos::ReprojectionScreend paper(hbos::HbosScreen::paper());
  CHECK(std::isnan(paper.screen(m).magnitude_cut()));
}

TEST_CASE("strategy names parse in the library, from one table", "[screen_v2][names]") {
  std::set<std::string> names;
  for (const hbos::NamedStrategy& s : hbos::named_strategies()) {
    CHECK(names.insert(s.name).second);
    CHECK_NOTHROW(hbos::ReprojectionScreend(hbos::parse_screen_strategy(s.name)));
  }
  CHECK(names.count("default") == 1);
  CHECK(names.count("paper") == 1);
  CHECK(names.count("chi2") == 1);
  CHECK(std::holds_alternative<hbos::ChiSquareGate>(hbos::parse_screen_strategy("chi2")));
  CHECK_THROWS_WITH(hbos::parse_screen_strategy("chi3"),
                    Catch::Contains("'chi3' is not one of default, paper"));
}

TEST_CASE("the v2 settings are validated", "[screen_v2][errors]") {
  hbos::HbosScreen s;
  s.gate.scale_quantile = 1.0;
  CHECK_THROWS_WITH(hbos::ReprojectionScreend(s), Catch::Contains("scale_quantile"));
  for (const double bad : {-0.1, std::nan(""), std::numeric_limits<double>::infinity()}) {
    s = hbos::HbosScreen{};
    s.gate.min_scale = bad;
    CHECK_THROWS_WITH(hbos::ReprojectionScreend(s), Catch::Contains("min_scale"));
  }
  s = hbos::HbosScreen{};
  s.coherence.depth_ratio = 1.0;
  CHECK_THROWS_WITH(hbos::ReprojectionScreend(s), Catch::Contains("depth_ratio"));
  s = hbos::HbosScreen{};
  s.threshold = hbos::AdaptiveRange{0.7};
  CHECK_THROWS_WITH(hbos::ReprojectionScreend(s), Catch::Contains("FixedThreshold"));
  hbos::Matchesd m;
  m.add(Vec2(1, 1), Vec2(2, 2));
  CHECK_THROWS_WITH(m.set_depth(0, -1.0), Catch::Contains("depth must be finite and > 0"));
  CHECK_THROWS_WITH(m.set_outlier_history(0, 1.5), Catch::Contains("[0, 1]"));
  CHECK_THROWS_WITH(m.set_mask_distance(0, std::nan("")), Catch::Contains("mask distance"));
}

TEMPLATE_TEST_CASE("fuzz finding: extreme matches never get a NaN score, whatever the strategy",
                   "[screen_v2][hardening]", float, double) {
  using Scalar = TestType;
  using V2 = Eigen::Matrix<Scalar, 2, 1>;
  using Limits = std::numeric_limits<Scalar>;
  // The finding: sigma = DBL_MAX on a stereo match whose right residual overflowed made
  // e^2 / sigma^2 = inf / inf in the gates. Such a sigma is now refused when it is added.
  hbos::Matches<Scalar> refused;
  CHECK_THROWS_WITH(refused.add(V2(1, 1), V2(2, 2), Limits::max()),
                    Catch::Contains("sigma") && Catch::Contains("out of range"));
  CHECK_THROWS_WITH(refused.add(V2(1, 1), V2(2, 2), Limits::min()),
                    Catch::Contains("out of range"));
  CHECK(refused.size() == 0);

  // Legal extremes: the smallest and largest legal sigma, residuals and right coordinates
  // that overflow, among a static background.
  const Scalar tiny = std::sqrt(Limits::min());
  const Scalar huge = Scalar(1) / tiny;
  hbos::Matches<Scalar> m;
  for (int i = 0; i < 30; ++i) {
    const V2 p(Scalar(20 * i), Scalar(15 * i));
    m.add(p, p + V2(Scalar(0.3), Scalar(-0.2)));
  }
  m.add(V2(5, 5), V2(6, 5), tiny);
  m.add(V2(5, 5), V2(6, 5), huge);
  m.add(V2(Limits::max(), 5), V2(-Limits::max(), 5), huge);
  m.add_stereo(V2(7, 7), V2(8, 7), Limits::max(), -Limits::max(), huge);
  m.add_stereo(V2(9, 9), V2(9, 9), -Limits::max(), Limits::max(), tiny);
  m.add(V2(Limits::lowest(), Limits::max()), V2(Limits::max(), Limits::lowest()), tiny);

  std::vector<hbos::ScreenStrategy> strategies;
  for (const auto& named : hbos::named_strategies()) strategies.push_back(named.make());
  strategies.emplace_back(hbos::QuantileGate{0.8, true});
  strategies.emplace_back(hbos::MadGate{3.0, false});
  for (const auto& strategy : strategies) {
    hbos::ScreenConfig config;
    config.strategy = strategy;
    hbos::ReprojectionScreen<Scalar> screen(config);
    const auto& r = screen.screen(m);
    INFO("strategy " << hbos::strategy_name(strategy));
    REQUIRE(r.size() == m.size());
    for (Eigen::Index i = 0; i < r.size(); ++i) {
      INFO("match " << i);
      CHECK_FALSE(std::isnan(r.score(i)));
    }
    // The overflowing matches are rejected by every strategy.
    for (Eigen::Index i = m.size() - 4; i < m.size(); ++i) CHECK_FALSE(r.inlier(i));
  }
}

TEST_CASE(
    "flagged consensus: a group of flagged new points moving together inside the gate vouches "
    "for itself, and the unflagged matches' evidence does not change",
    "[screen_v2][coherence]") {
  const double s = 0.4;
  hbos::Matchesd m = static_matches(400, s, 41);
  // The room's own new points: flagged, scattered, at the room's depth, with its noise.
  const Eigen::Index room_new = m.size();
  add_object(m, 60, Vec2::Zero(), s, 0.0, 0.0, 640.0, 480.0, 2.0, 42, true);
  // A person's new points: flagged, 1.6 px/sigma off (inside chi^2's gate), nearer.
  const Eigen::Index person = m.size();
  add_object(m, 80, Vec2(1.6, 0.3), s, 400.0, 150.0, 120.0, 200.0, 0.9, 43, true);
  REQUIRE(m.flagged_count() == 140);

  // Without it, no match of the fit set sits among the person's new points: no consensus,
  // nothing fires, and the magnitude alone keeps them.
  hbos::ReprojectionScreend plain;
  const auto& r0 = plain.screen(m);
  CHECK(rejected_share(r0, person, m.size()) < 0.2);
  std::vector<double> unflagged_coherence(static_cast<std::size_t>(room_new));
  for (Eigen::Index i = 0; i < room_new; ++i)
    unflagged_coherence[static_cast<std::size_t>(i)] = r0.coherence(i);
  const std::vector<std::uint8_t> unflagged_kept(r0.inliers().data(),
                                                 r0.inliers().data() + room_new);

  hbos::HbosScreen with;
  with.coherence.flagged_consensus = true;
  hbos::ReprojectionScreend consensus(with);
  const auto& r1 = consensus.screen(m);
  CHECK(rejected_share(r1, person, m.size()) > 0.8);
  CHECK(rejected_share(r1, room_new, person) < 0.05);
  CHECK(rejected_share(r1, 0, room_new) < 0.02);
  // The fit set's consensus is its own: every unflagged match's evidence is unchanged.
  for (Eigen::Index i = 0; i < room_new; ++i) {
    CHECK(r1.coherence(i) == unflagged_coherence[static_cast<std::size_t>(i)]);
    CHECK(r1.inlier(i) == (unflagged_kept[static_cast<std::size_t>(i)] != 0));
  }

  SECTION("without flags the option changes nothing") {
    hbos::Matchesd unflagged = static_matches(400, s, 43);
    add_object(unflagged, 80, Vec2(1.6, 0.3), s, 400.0, 150.0, 120.0, 200.0, 0.9, 44);
    const auto& a = plain.screen(unflagged);
    const std::vector<double> scores(a.scores().data(), a.scores().data() + a.size());
    const auto& b = consensus.screen(unflagged);
    for (Eigen::Index i = 0; i < b.size(); ++i)
      CHECK(b.score(i) == scores[static_cast<std::size_t>(i)]);
  }
}
