#include "render/scenario.hpp"

#include <cmath>

#include "render/random.hpp"
#include "render/room.hpp"

namespace hbos::render {
namespace {

constexpr double kFaceCamera = kPi;  // heading towards -y, where the camera is
// Where an action that goes nowhere points: `{}` would leave an Eigen vector uninitialised.
const Eigen::Vector2d kNowhere = Eigen::Vector2d::Zero();

Action walk(double x, double y) { return {Action::Kind::kWalk, {x, y}, 0.0, 0.0}; }
Action wait(double s) { return {Action::Kind::kWait, kNowhere, s, 0.0}; }
Action turn(double yaw, double s) { return {Action::Kind::kTurn, kNowhere, s, yaw}; }
Action sit(double yaw) { return {Action::Kind::kSit, kNowhere, 1.2, yaw}; }
Action stand() { return {Action::Kind::kStand, kNowhere, 1.2, 0.0}; }
Action swivel(double yaw, double s) { return {Action::Kind::kSwivel, kNowhere, s, yaw}; }

// The person who carries a box around the desk, crossing between the camera and the desk.
PersonSpec carrier() {
  PersonSpec p;
  p.role = "walks around the desk carrying a box, crosses in front of the camera, stops, turns";
  p.start = {-2.2, 0.8};
  p.start_yaw = heading({1.0, -1.0});
  p.actions = {walk(-1.3, -1.0), walk(1.2, -1.0),
               wait(1.5),        turn(kFaceCamera, 1.0),
               wait(1.0),        walk(1.6, 1.1),
               walk(0.0, 1.42),  wait(2.0),
               walk(-2.2, 0.8),  turn(heading({1.0, -1.0}), 0.8)};
  p.carries = true;
  p.look = 0;
  return p;
}

// Sits at the right chair, talks (swivels), gets up, walks a loop in front of the desk, sits.
PersonSpec sitter_walker(const RoomLayout& room) {
  PersonSpec p;
  p.role = "sits at the desk, swivels, stands up, walks in front of the desk, sits down again";
  p.start = room.chair_right;
  p.start_yaw = kFaceCamera;
  p.start_seated = true;
  p.actions = {wait(3.0),
               swivel(0.5, 3.0),
               wait(2.0),
               stand(),
               walk(1.3, 0.9),
               walk(1.3, -1.25),
               walk(-0.6, -1.3),
               turn(kFaceCamera, 1.0),
               wait(2.0),
               walk(-1.5, 0.2),
               walk(-1.0, 1.42),
               walk(0.45, 1.42),
               walk(room.chair_right.x(), room.chair_right.y()),
               sit(kFaceCamera)};
  p.look = 1;
  p.height_scale = 0.97f;
  return p;
}

// Walks along the back of the room, sits at the left chair for a while, goes back.
PersonSpec back_walker(const RoomLayout& room) {
  PersonSpec p;
  p.role = "walks along the back, sits at the left chair, swivels, stands, walks back";
  p.start = {2.4, 1.05};
  p.start_yaw = heading({-1.0, 0.0});
  p.actions = {walk(-0.4, 1.42),  walk(room.chair_left.x(), room.chair_left.y()),
               sit(kFaceCamera),  wait(4.0),
               swivel(-0.6, 3.0), wait(2.0),
               stand(),           walk(-0.4, 1.42),
               walk(2.4, 1.05),   turn(heading({-1.0, 0.0}), 1.0),
               wait(2.0)};
  p.look = 2;
  p.height_scale = 1.03f;
  return p;
}

// Seated the whole time, talking: swivels on the chair, (the first) holding a box.
PersonSpec seated(const Eigen::Vector2d& chair, double swing, bool carries, int look) {
  PersonSpec p;
  p.role = carries ? "sits at the desk holding a box, swivels to talk"
                   : "sits at the desk, swivels to talk";
  p.start = chair;
  p.start_yaw = kFaceCamera;
  p.start_seated = true;
  p.actions = {wait(2.5), swivel(swing, 3.0), wait(2.0), swivel(-0.8 * swing, 2.5), wait(3.5)};
  p.carries = carries;
  p.look = look;
  return p;
}

struct Entry {
  const char* name;
  const char* trajectory;
  bool sitting;
  int default_people;
};

const Entry kEntries[] = {
    {"walking_xyz", "fr3_walking_xyz_groundtruth.txt", false, 2},
    {"walking_static", "fr3_walking_static_groundtruth.txt", false, 2},
    {"walking_rpy", "fr3_walking_rpy_groundtruth.txt", false, 2},
    {"walking_halfsphere", "fr3_walking_halfsphere_groundtruth.txt", false, 2},
    {"sitting_static", "fr3_sitting_static_groundtruth.txt", true, 2},
    {"sitting_xyz", "fr3_sitting_xyz_groundtruth.txt", true, 2},
};

// The seed's variation: walk targets +-0.12 m (not the chairs, not the loop's start), waits x
// 0.7..1.3, speed 0.75..1.05 m/s, and the phase of each loop at frame 0.
void jitter(PersonSpec& p, Rng& rng) {
  for (std::size_t i = 0; i < p.actions.size(); ++i) {
    Action& a = p.actions[i];
    const bool to_chair = i + 1 < p.actions.size() && p.actions[i + 1].kind == Action::Kind::kSit;
    if (a.kind == Action::Kind::kWalk && !to_chair && (a.to - p.start).norm() > 1e-9) {
      a.to += Eigen::Vector2d(rng.uniform(-0.12, 0.12), rng.uniform(-0.12, 0.12));
    }
    if (a.kind == Action::Kind::kWait) a.duration *= rng.uniform(0.7, 1.3);
  }
  p.speed = rng.uniform(0.75, 1.05);
  p.start_fraction = rng.uniform();
}

}  // namespace

const std::vector<std::string>& scenario_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const Entry& e : kEntries) n.emplace_back(e.name);
    return n;
  }();
  return names;
}

Scenario make_scenario(const std::string& name, std::uint64_t seed, int people) {
  const Entry* entry = nullptr;
  for (const Entry& e : kEntries) {
    if (name == e.name) entry = &e;
  }
  if (entry == nullptr) {
    std::string list;
    for (const auto& n : scenario_names()) list += (list.empty() ? "" : ", ") + n;
    throw UsageError("unknown scenario '" + name + "' (known: " + list + ")");
  }
  if (people == -1) people = entry->default_people;
  if (people < 1 || people > 3) {
    throw UsageError("--people must be 1, 2 or 3 (got " + std::to_string(people) + ")");
  }
  const RoomLayout room;
  Scenario s;
  s.name = entry->name;
  s.trajectory_file = entry->trajectory;
  std::vector<PersonSpec> cast;
  if (entry->sitting) {
    s.description = "two people sit at the desk and talk, one holds a box; a third walks by";
    cast = {seated(room.chair_left, 0.6, true, 0), seated(room.chair_right, -0.7, false, 1),
            back_walker(room)};
    // The walker cannot sit at the occupied left chair: they only walk the back and pause.
    cast[2].actions = {walk(-1.4, 0.9), turn(kFaceCamera, 1.0),          wait(3.0),
                       walk(2.4, 1.05), turn(heading({-1.0, 0.0}), 1.0), wait(2.0)};
    cast[2].role = "walks along the back of the room, stops, turns, walks back";
  } else {
    s.description = "people walk around the desk, one carrying a box; others sit, swivel, stand up";
    cast = {carrier(), sitter_walker(room), back_walker(room)};
  }
  cast.resize(static_cast<std::size_t>(people));
  Rng rng = stream(seed, Stream::kScript);
  for (PersonSpec& p : cast) jitter(p, rng);
  s.people = cast;
  return s;
}

}  // namespace hbos::render
