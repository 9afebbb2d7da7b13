#include "render/script.hpp"

#include <algorithm>
#include <cmath>

namespace hbos::render {
namespace {

constexpr double kStride = 1.3;  // [m] one gait cycle (two steps)

double wrap(double a) {
  while (a > kPi) a -= 2 * kPi;
  while (a < -kPi) a += 2 * kPi;
  return a;
}

}  // namespace

double heading(const Eigen::Vector2d& d) { return std::atan2(-d.x(), d.y()); }

Timeline::Timeline(const Eigen::Vector2d& start, double start_yaw, bool start_seated,
                   const std::vector<Action>& actions, double speed, double turn_rate,
                   double start_fraction) {
  Key k{0.0, BodyState{}, 0.0};
  k.s.position = start;
  k.s.yaw = start_yaw;
  k.s.sit = start_seated ? 1.0 : 0.0;
  keys_.push_back(k);
  auto push = [&](double dt, const BodyState& s, double dist) {
    Key n{keys_.back().t + std::max(dt, 1e-3), s, dist};
    keys_.push_back(n);
  };
  for (const Action& a : actions) {
    const Key last = keys_.back();
    BodyState s = last.s;
    s.walking = 0.0;
    switch (a.kind) {
      case Action::Kind::kWalk: {
        const Eigen::Vector2d d = a.to - s.position;
        const double len = d.norm();
        if (len < 1e-6) break;
        const double target = heading(d);
        const double turn = wrap(target - s.yaw);
        if (std::abs(turn) > 1e-3) {
          s.yaw = s.yaw + turn;
          push(std::abs(turn) / turn_rate, s, last.distance);
        }
        // Accelerate into the stride, walk, and settle: the swing amplitude follows.
        BodyState w = s;
        w.walking = 1.0;
        const double ramp = std::min(0.3, 0.25 * len);
        w.position = s.position + d * (ramp / len);
        push(2.0 * ramp / speed, w, last.distance + ramp);
        w.position = a.to - d * (ramp / len);
        push((len - 2.0 * ramp) / speed, w, last.distance + len - ramp);
        BodyState e = w;
        e.position = a.to;
        e.walking = 0.0;
        push(2.0 * ramp / speed, e, last.distance + len);
        break;
      }
      case Action::Kind::kWait:
        push(a.duration, s, last.distance);
        break;
      case Action::Kind::kTurn:
        s.yaw = s.yaw + wrap(a.yaw - s.yaw);
        push(a.duration, s, last.distance);
        break;
      case Action::Kind::kSit:
        s.yaw = s.yaw + wrap(a.yaw - s.yaw);
        push(0.4, s, last.distance);
        s.sit = 1.0;
        push(a.duration, s, last.distance);
        break;
      case Action::Kind::kStand:
        s.sit = 0.0;
        push(a.duration, s, last.distance);
        break;
      case Action::Kind::kSwivel: {
        const double base = s.yaw;
        s.yaw = base + a.yaw;
        s.head_yaw = 0.3 * a.yaw;
        push(0.3 * a.duration, s, last.distance);
        push(0.4 * a.duration, s, last.distance);
        s.yaw = base;
        s.head_yaw = 0.0;
        push(0.3 * a.duration, s, last.distance);
        break;
      }
    }
  }
  // Scripts end where they start; an unwrapped heading is brought back to the start's.
  keys_.back().s.yaw = keys_.front().s.yaw + wrap(keys_.back().s.yaw - keys_.front().s.yaw);
  t_offset_ = start_fraction * period();
}

BodyState Timeline::at(double t) const {
  const double T = period();
  double tl = std::fmod(t + t_offset_, T);
  if (tl < 0) tl += T;
  const auto it = std::upper_bound(keys_.begin(), keys_.end(), tl,
                                   [](double v, const Key& k) { return v < k.t; });
  const Key& b = it == keys_.end() ? keys_.back() : *it;
  const Key& a = it == keys_.begin() ? keys_.front() : *(it - 1);
  const double s = b.t > a.t ? std::clamp((tl - a.t) / (b.t - a.t), 0.0, 1.0) : 1.0;
  // Smooth sitting and turning (ease in/out); positions and stride run linearly.
  const double e = s * s * (3.0 - 2.0 * s);
  BodyState out;
  out.position = (1.0 - s) * a.s.position + s * b.s.position;
  out.yaw = a.s.yaw + e * wrap(b.s.yaw - a.s.yaw);
  out.sit = (1.0 - e) * a.s.sit + e * b.s.sit;
  out.walking = (1.0 - s) * a.s.walking + s * b.s.walking;
  out.head_yaw = (1.0 - e) * a.s.head_yaw + e * b.s.head_yaw;
  const double dist = (1.0 - s) * a.distance + s * b.distance;
  out.gait_phase = 2.0 * kPi * dist / kStride;
  return out;
}

}  // namespace hbos::render
