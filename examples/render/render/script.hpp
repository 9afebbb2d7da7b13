#pragma once
/// \file
/// People's scripts: what each person does, as a list of actions turned into a timeline of body
/// states (where they stand, which way they face, how far they sit, how their limbs swing).

#include <vector>

#include <Eigen/Core>

namespace hbos::render {

/// pi, for headings and gait phases.
inline constexpr double kPi = 3.14159265358979323846;

/// One step of a script.
struct Action {
  enum class Kind {
    kWalk,    ///< turn towards `to`, then walk there at the script's speed
    kWait,    ///< stand (or sit) still for `duration`
    kTurn,    ///< turn on the spot to face `yaw` over `duration`
    kSit,     ///< sit down where one stands, facing `yaw` (a chair is there), over `duration`
    kStand,   ///< stand up over `duration`
    kSwivel,  ///< seated: turn the chair by +-`yaw` and back over `duration` (talking, looking)
  };
  Kind kind = Kind::kWait;
  Eigen::Vector2d to = Eigen::Vector2d::Zero();  ///< [m] room frame (kWalk)
  double duration = 1.0;                         ///< [s]
  double yaw = 0.0;                              ///< [rad] (kTurn, kSit: heading; kSwivel: swing)
};

/// Where a body is and what its limbs do at one instant.
struct BodyState {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  ///< [m] hip centre on the floor
  double yaw = 0.0;         ///< [rad] heading: the body faces (-sin yaw, cos yaw)
  double sit = 0.0;         ///< 0 standing .. 1 seated
  double gait_phase = 0.0;  ///< [rad] 2 pi per stride pair
  double walking = 0.0;     ///< 0 still .. 1 full stride (limb swing amplitude)
  double head_yaw = 0.0;    ///< [rad] relative to the body
};

/// A person's script compiled into piecewise-linear keyframes; loops when it ends (scripts end
/// where they start, so the loop is seamless).
class Timeline {
 public:
  /// Compiles `actions` from a start position and heading, walking at `speed` [m/s] and
  /// turning at `turn_rate` [rad/s]. Time 0 of the sequence is `start_fraction` (0..1) of the
  /// way into the loop.
  Timeline(const Eigen::Vector2d& start, double start_yaw, bool start_seated,
           const std::vector<Action>& actions, double speed, double turn_rate,
           double start_fraction);

  /// The body at time `t` [s] since the sequence start.
  BodyState at(double t) const;

  /// [s] length of one loop.
  double period() const { return keys_.back().t; }

 private:
  struct Key {
    double t;
    BodyState s;
    double distance;  // [m] walked so far (drives the gait phase)
  };
  std::vector<Key> keys_;
  double t_offset_ = 0.0;
};

/// Heading that faces along (dx, dy).
double heading(const Eigen::Vector2d& direction);

}  // namespace hbos::render
