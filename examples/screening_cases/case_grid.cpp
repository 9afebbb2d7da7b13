#include "case_spec.hpp"

namespace hbos::cases {

const char* to_string(MaskKind kind) {
  switch (kind) {
    case MaskKind::kNone:
      return "none";
    case MaskKind::kDegraded:
      return "degraded";
    case MaskKind::kExact:
      return "exact";
  }
  return "?";
}

const char* to_string(RoughPoseKind kind) {
  switch (kind) {
    case RoughPoseKind::kRansac:
      return "ransac";
    case RoughPoseKind::kPerturbed:
      return "pgt";
  }
  return "?";
}

namespace {

// A person: which, its size and depth in the first frame, where (box centre, px), and its world
// velocity [m/s] in the first camera's axes (x right, y down, z forward).
PersonMotion person(char id, double scale, double depth_m, double u, double v, double vx, double vy,
                    double vz) {
  PersonMotion m;
  m.person = id;
  m.scale = scale;
  m.depth_m = depth_m;
  m.start_px = {u, v};
  m.velocity_m_s = {vx, vy, vz};
  return m;
}

CaseSpec make(std::string name, std::string speed, std::vector<PersonMotion> people, MaskKind mask,
              std::uint64_t seed) {
  CaseSpec c;
  c.name = std::move(name);
  c.speed = std::move(speed);
  c.people = std::move(people);
  c.mask = mask;
  c.seed = seed;
  return c;
}

constexpr MaskKind kNone = MaskKind::kNone, kDegraded = MaskKind::kDegraded,
                   kExact = MaskKind::kExact;

}  // namespace

// Speeds [m/s] (30 Hz, ~32 ms between frames): slow 0.1-0.25 (0.3-0.8 cm per frame, residuals
// near the noise at 1 m), medium 0.5-0.6, walk 1.0-1.4. Person A is the seated man (left of the
// fr3 frame), B the standing man (right, cut by the image edge).
std::vector<CaseSpec> fixture_grid() {
  const PersonMotion a_slow = person('A', 1.6, 0.9, 230, 270, 0.15, 0.0, 0.0);
  const PersonMotion b_toward = person('B', 1.0, 1.4, 470, 240, -0.15, 0.0, -0.4);
  const PersonMotion b_walk = person('B', 1.0, 1.4, 520, 290, -1.2, 0.0, 0.0);
  return {
      make("static", "static", {}, kNone, 1),
      make("a_slow_none", "slow", {a_slow}, kNone, 2),
      make("a_slow_degraded", "slow", {a_slow}, kDegraded, 3),
      make("b_toward_degraded", "medium", {b_toward}, kDegraded, 6),
      make("ab_mixed_none", "mixed", {person('A', 1.1, 1.1, 170, 300, 0.1, 0.0, 0.0), b_walk},
           kNone, 7),
      make("b_walk_exact", "walk", {b_walk}, kExact, 8),
      make("b_slow_none", "slow", {person('B', 1.0, 1.0, 500, 240, -0.1, 0.0, 0.0)}, kNone, 9),
  };
}

std::vector<CaseSpec> holdout_grid() {
  const PersonMotion b_slow = person('B', 1.0, 1.1, 420, 240, 0.1, 0.0, 0.0);
  const PersonMotion a_toward = person('A', 0.8, 2.0, 320, 280, 0.3, 0.0, -1.2);
  std::vector<CaseSpec> g = {
      make("h_static_reverse", "static", {}, kNone, 101),
      make("h_b_slow_none", "slow", {b_slow}, kNone, 102),
      make("h_a_toward_degraded", "walk", {a_toward}, kDegraded, 105),
      make("h_ab_slow_none", "slow",
           {person('A', 1.0, 1.2, 150, 300, 0.2, 0.0, 0.0),
            person('B', 1.0, 1.0, 480, 240, -0.12, 0.0, 0.0)},
           kNone, 106),
  };
  // Played backwards: pairs (i+1 -> i) the fixture never has; another degradation.
  g[0].reverse = true;
  g[2].reverse = true;
  g[2].degradation = {4, 0.3, 4};
  return g;
}

std::vector<CaseSpec> static_grid() {
  std::vector<CaseSpec> g = {make("static", "static", {}, kNone, 1),
                             make("static_reverse", "static", {}, kNone, 101)};
  g[1].reverse = true;
  return g;
}

}  // namespace hbos::cases
