// Proves the per-frame screening path allocates nothing after warm-up, for every strategy, in
// single and iterated mode, with frames of varying size (allocations, operator new and malloc
// alike, are counted in tests/unit/alloc_counter.cpp).

#include <catch2/catch.hpp>

#include <hbos/screening.hpp>

#include <vector>

#include "../support/alloc_counter.hpp"
#include "../support/screening_eval.hpp"
#include "../support/synthetic_scene.hpp"

TEST_CASE("screening allocates nothing after warm-up", "[reprojection][alloc]") {
  std::vector<hbos_test::Scene> scenes;
  for (int n : {5000, 300, 2000, 100, 5000}) {
    hbos_test::SceneConfig c;
    c.seed = static_cast<std::uint64_t>(n);
    c.n_matches = n;
    c.person_share = 0.1;
    c.gross_share = 0.05;
    c.masked_person_share = 0.05;
    scenes.push_back(hbos_test::make_scene(c));
  }
  hbos::HbosScreen with_angle = hbos::HbosScreen::magnitude_only();
  with_angle.angle = hbos::AngleFeature::AboveNoise;
  hbos::HbosScreen flagged_consensus;  // the map tracker's setting: a second pass on the flagged
  flagged_consensus.coherence.flagged_consensus = true;
  const std::vector<hbos::ScreenStrategy> strategies{hbos::HbosScreen{},
                                                     flagged_consensus,
                                                     hbos::HbosScreen::paper(),
                                                     hbos::HbosScreen::magnitude_only(),
                                                     with_angle,
                                                     hbos::ChiSquareGate{},
                                                     hbos::FixedPixelGate{},
                                                     hbos::QuantileGate{},
                                                     hbos::MadGate{}};
  const hbos::PinholeCamerad camera;
  hbos::IteratedScreenOptions later_floor;
  later_floor.later_gate_floor = 2.0;
  later_floor.later_rigid_field = true;  // and a rigid refit: six sums and a 6 x 6 solve

  for (const auto& strategy : strategies) {
    INFO("strategy " << hbos::strategy_name(strategy));
    hbos::ReprojectionScreend screen(strategy);
    screen.reserve(5000);
    hbos::Matchesd matches;
    matches.reserve(5000);
    // Warm-up: one frame of the largest size through both paths.
    hbos_test::load_matches(scenes[0], matches);
    screen.screen(matches);
    Eigen::Isometry3d T = scenes[0].T_cur_world_rough;
    hbos::screen_and_refine_pose(screen, scenes[0].points_world, camera, T, matches);
    hbos_test::load_matches(scenes[0], matches);
    T = scenes[0].T_cur_world_rough;
    hbos::screen_and_refine_pose(screen, scenes[0].points_world, camera, T, matches, later_floor);

    hbos_test::AllocationCounter counter;
    Eigen::Index kept = 0;
    for (const auto& scene : scenes) {
      hbos_test::load_matches(scene, matches);
      kept += screen.screen(matches).n_inliers();
      Eigen::Isometry3d T_cur_world = scene.T_cur_world_rough;
      kept += hbos::screen_and_refine_pose(screen, scene.points_world, camera, T_cur_world, matches)
                  .n_inliers();
      // The rounds with a lower gate floor and a rigid refit after the first switch the screen's
      // config back and forth: that copies a config, nothing more.
      hbos_test::load_matches(scene, matches);
      T_cur_world = scene.T_cur_world_rough;
      kept += hbos::screen_and_refine_pose(screen, scene.points_world, camera, T_cur_world, matches,
                                           later_floor)
                  .n_inliers();
    }
    CHECK(counter.count() == 0);
    CHECK(kept > 0);
  }
}

TEST_CASE("reserve alone is enough: the first frame does not allocate", "[reprojection][alloc]") {
  hbos_test::SceneConfig c;
  c.n_matches = 1000;
  c.gross_share = 0.05;
  const hbos_test::Scene scene = hbos_test::make_scene(c);
  hbos::ReprojectionScreend screen;
  screen.reserve(1000);
  hbos::Matchesd matches;
  matches.reserve(1000);
  hbos_test::AllocationCounter counter;
  hbos_test::load_matches(scene, matches);
  const auto& result = screen.screen(matches);
  CHECK(counter.count() == 0);
  CHECK(result.size() == 1000);
}

TEST_CASE("Matches::assign allocates nothing once reserved", "[reprojection][alloc]") {
  hbos_test::SceneConfig c;
  c.n_matches = 1000;
  c.masked_person_share = 0.05;
  const hbos_test::Scene scene = hbos_test::make_scene(c);
  hbos::Matchesd matches;
  matches.reserve(1000);
  hbos_test::AllocationCounter counter;
  matches.assign(scene.predicted, scene.observed, scene.sigma, scene.on_dynamic_mask);
  CHECK(counter.count() == 0);
  CHECK(matches.size() == 1000);
}
