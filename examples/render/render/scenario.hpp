#pragma once
/// \file
/// The named scenarios: a real fr3 camera path plus a script for each person, made concrete by a
/// seed (the seed jitters where people walk, how fast, how long they pause and where in their
/// loop the sequence starts).

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/script.hpp"

namespace hbos::render {

/// A usage error in what was asked for (unknown scenario, bad count); `what()` says which.
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// One person of a scenario.
struct PersonSpec {
  std::string role;                                 ///< what they do, for scenario.json
  Eigen::Vector2d start = Eigen::Vector2d::Zero();  ///< [m] room frame
  double start_yaw = 0.0;                           ///< [rad]
  bool start_seated = false;
  std::vector<Action> actions;  ///< one loop, ending where it starts
  bool carries = false;         ///< holds a box (its own object id)
  int look = 0;                 ///< outfit 0..2
  float height_scale = 1.f;     ///< body size factor
  double speed = 0.9;           ///< [m/s] walking speed
  double start_fraction = 0.0;  ///< where in the loop frame 0 falls (0..1)
};

/// A scenario: camera path and people.
struct Scenario {
  std::string name;
  std::string description;
  std::string trajectory_file;  ///< under data/trajectories/
  std::vector<PersonSpec> people;
};

/// The scenario names, in documentation order.
const std::vector<std::string>& scenario_names();

/// The scenario `name` for `seed`, with `people` persons (1..3; -1 = the scenario's default).
/// \throws UsageError for an unknown name or a people count out of range.
Scenario make_scenario(const std::string& name, std::uint64_t seed, int people);

}  // namespace hbos::render
