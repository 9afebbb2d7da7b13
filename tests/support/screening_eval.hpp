#pragma once
/// \file
/// The labelled evaluation of reprojection screens on synthetic scenes, shared by the acceptance
/// tests (tests/unit/test_screen_acceptance.cpp) and the study (examples/screening_study), so both
/// measure exactly the same thing. Test support, not part of the library.

#include <hbos/screening.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "synthetic_scene.hpp"

namespace hbos_test {

/// Which kind of dynamic matches leak past the mask.
enum class Scenario { Static, Person, Edges, Carried, Mixed };

[[nodiscard]] inline const char* scenario_name(Scenario s) {
  switch (s) {
    case Scenario::Static:
      return "static";
    case Scenario::Person:
      return "person";
    case Scenario::Edges:
      return "edges";
    case Scenario::Carried:
      return "carried";
    case Scenario::Mixed:
      return "mixed";
  }
  return "?";
}

/// The grid point's conditions besides scenario and leakage.
struct Conditions {
  int n_matches = 1000;   ///< matches per frame
  double noise_px = 0.5;  ///< [px] per-axis keypoint noise at octave 0 (measured on TUM fr1/xyz)
  double pose_error_min = 0.0;  ///< [px] the rough pose's median static residual is drawn
  double pose_error_max = 3.0;  ///< uniformly from [min, max] per seed
  double gross_max = 0.05;      ///< gross mismatch share drawn uniformly from [0, gross_max]
  bool iterated = false;        ///< screen -> Gauss-Newton refit -> re-screen (4 rounds)
};

/// The scene of one seed: `leak` is the share of the matches that are dynamic and unflagged.
/// Mixed = 70 % person, 15 % silhouette edges, 15 % carried object.
[[nodiscard]] inline SceneConfig scenario_config(Scenario scenario, double leak, std::uint64_t seed,
                                                 const Conditions& c) {
  SceneConfig config;
  config.seed = seed;
  config.n_matches = c.n_matches;
  config.noise_px = c.noise_px;
  // Per-seed conditions come from their own stream so that they do not depend on the scenario.
  detail::Random conditions(seed * 0x9E3779B97F4A7C15ull + 17u);
  config.pose_error_px = conditions.uniform(c.pose_error_min, c.pose_error_max);
  config.gross_share = conditions.uniform(0.0, c.gross_max);
  switch (scenario) {
    case Scenario::Static:
      break;
    case Scenario::Person:
      config.person_share = leak;
      break;
    case Scenario::Edges:
      config.edge_share = leak;
      break;
    case Scenario::Carried:
      config.carried_share = leak;
      break;
    case Scenario::Mixed:
      config.person_share = 0.70 * leak;
      config.edge_share = 0.15 * leak;
      config.carried_share = 0.15 * leak;
      break;
  }
  return config;
}

/// Loads a scene into a reusable Matches (monocular, with sigma and the prior flag).
/// The share of matches first..last-1 the screen rejected.
[[nodiscard]] inline double rejected_share(const hbos::ScreenResult<double>& r, Eigen::Index first,
                                           Eigen::Index last) {
  Eigen::Index rejected = 0;
  for (Eigen::Index i = first; i < last; ++i) rejected += r.inlier(i) ? 0 : 1;
  return static_cast<double>(rejected) / static_cast<double>(last - first);
}

inline void load_matches(const Scene& scene, hbos::Matches<double>& matches) {
  matches.clear();
  matches.reserve(scene.size());
  for (Eigen::Index i = 0; i < scene.size(); ++i)
    matches.add(scene.predicted.col(i), scene.observed.col(i), scene.sigma(i),
                scene.on_dynamic_mask(i));
}

/// Screens one scene (iterated or not) and returns the survival tally.
inline Tally screen_scene(hbos::ReprojectionScreen<double>& screen, const Scene& scene,
                          hbos::Matches<double>& matches, bool iterated) {
  load_matches(scene, matches);
  Tally tally;
  if (iterated) {
    const hbos::PinholeCamera<double> camera{scene.fx, scene.fy, scene.cx, scene.cy};
    Eigen::Isometry3d T_cur_world = scene.T_cur_world_rough;
    const auto& result =
        hbos::screen_and_refine_pose(screen, scene.points_world, camera, T_cur_world, matches);
    tally.add_scene(scene, result.inliers());
  } else {
    tally.add_scene(scene, screen.screen(matches).inliers());
  }
  return tally;
}

/// Every strategy on the same scenes: seeds [first_seed, first_seed + seeds). One tally each.
[[nodiscard]] inline std::vector<Tally> evaluate(
    const std::vector<hbos::ScreenStrategy>& strategies, Scenario scenario, double leak,
    std::uint64_t first_seed, int seeds, const Conditions& conditions) {
  std::vector<hbos::ReprojectionScreen<double>> screens;
  for (const auto& s : strategies) screens.emplace_back(s);
  std::vector<Tally> tallies(strategies.size());
  hbos::Matches<double> matches;
  for (int k = 0; k < seeds; ++k) {
    const Scene scene = make_scene(
        scenario_config(scenario, leak, first_seed + static_cast<std::uint64_t>(k), conditions));
    for (std::size_t s = 0; s < screens.size(); ++s)
      tallies[s] += screen_scene(screens[s], scene, matches, conditions.iterated);
  }
  return tallies;
}

}  // namespace hbos_test
