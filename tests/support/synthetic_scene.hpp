#pragma once
/// \file
/// Seeded synthetic correspondences with known truth, for testing and studying reprojection
/// screens. Header-only, Eigen only. Test support, not part of the library.
///
/// Geometry. The world frame is the previous camera's frame. Every match is a 3D map point
/// `X_w`, reprojected with the *rough* pose to give the predicted pixel, and a keypoint observed in
/// the current frame. The truth:
///
///     observed  = pi(T_cur_world_true  * (X_w + motion)) + noise,   noise ~ N(0,
///     (noise_px*sigma)^2 I) predicted = pi(T_cur_world_rough *  X_w)
///
/// with `pi` the TUM3 pinhole (fx 535.4, fy 539.2, cx 320.1, cy 247.6; 640 x 480), `sigma` =
/// 1.2^octave (ORB-SLAM's scale pyramid: octaves 0..7 drawn with probability proportional to
/// 1.2^-octave, as ORB-SLAM spreads its features over the levels) and `motion` zero for static
/// points. The rough pose is the true one perturbed by a random small rotation (including roll)
/// and translation, scaled so that the *median* noise-free residual of the static matches equals
/// `pose_error_px`: a coherent residual field that varies over the image with depth and position.
///
/// Labels (everything but Static should be rejected by a screen):
/// - Static: background at depth 0.5-4 m, uniform over the image.
/// - DynamicPerson: a walking person, a cluster of points in a 100-180 x 250-400 px box at depth
///   0.6-1.5 m, moving by a common 3D velocity of `person_speed_*` per frame, mostly sideways,
///   plus a per-point limb variation (25 % of the speed).
/// - Edge: keypoints on the person's silhouette, a corner formed by person and background: the
///   point is on either side of the boundary and moves by a random 20-100 % of the person's motion.
/// - CarriedObject: a small rigid object (40-80 px box, depth 0.45-1.0 m) moved by the hand: the
///   person's velocity plus its own 1-4 cm per frame and a rotation of up to 3 degrees.
/// - GrossMismatch: a wrong match: the observation lies 8-300 px (log-uniform) from the prediction
///   in a random direction.
///
/// The dynamic-mask prior: `masked_person_share` adds further person matches flagged
/// `on_dynamic_mask` (the part a detector's mask covers); all shares named `*_share` are fractions
/// of `n_matches`, and everything not flagged has leaked past the mask.
///
/// Randomness comes from std::mt19937_64 (fully specified by the standard) with our own uniform
/// and Box-Muller transforms, so a seed gives the same scene on every standard library.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace hbos_test {

/// What a synthetic match really is.
enum class Label : std::uint8_t { Static, DynamicPerson, Edge, CarriedObject, GrossMismatch };
inline constexpr int kLabelCount = 5;

[[nodiscard]] inline const char* label_name(Label label) {
  switch (label) {
    case Label::Static:
      return "static";
    case Label::DynamicPerson:
      return "person";
    case Label::Edge:
      return "edge";
    case Label::CarriedObject:
      return "carried";
    case Label::GrossMismatch:
      return "gross";
  }
  return "?";
}

/// True for the labels a screen should reject because they move (not gross mismatches).
[[nodiscard]] inline bool is_dynamic(Label label) {
  return label == Label::DynamicPerson || label == Label::Edge || label == Label::CarriedObject;
}

struct SceneConfig {
  std::uint64_t seed = 1;            ///< the scene is a pure function of the config
  int n_matches = 1000;              ///< total matches, >= 10
  double person_share = 0.0;         ///< leaked (unflagged) walking-person matches, share of n
  double edge_share = 0.0;           ///< leaked silhouette-edge matches, share of n
  double carried_share = 0.0;        ///< leaked carried-object matches, share of n
  double gross_share = 0.0;          ///< gross mismatches, share of n
  double masked_person_share = 0.0;  ///< person matches flagged on the dynamic mask, share of n
  double pose_error_px = 1.5;        ///< [px] median noise-free residual of static matches, >= 0
  double noise_px = 0.5;             ///< [px] per-axis keypoint noise std at octave 0 (x sigma)
  double person_speed_min = 0.005;   ///< [m/frame] slowest walking speed
  double person_speed_max = 0.02;    ///< [m/frame] fastest walking speed
  double camera_step = 0.0107;       ///< [m/frame] true camera translation (TUM fr1/xyz's mean)
  int octaves = 8;                   ///< ORB pyramid levels
  double scale_factor = 1.2;         ///< ORB pyramid scale
};

/// One synthetic frame pair: the inputs of a screen plus the truth.
struct Scene {
  Eigen::Matrix2Xd predicted;     ///< [px] map points reprojected with the rough pose
  Eigen::Matrix2Xd observed;      ///< [px] keypoints in the current frame
  Eigen::Matrix3Xd points_world;  ///< [m] the map points
  std::vector<int> octave;        ///< ORB octave of each keypoint
  Eigen::ArrayXd sigma;           ///< scale_factor^octave
  Eigen::Array<bool, Eigen::Dynamic, 1> on_dynamic_mask;  ///< the prior flag
  std::vector<Label> label;                               ///< the truth
  Eigen::Isometry3d T_cur_world_true = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_cur_world_rough = Eigen::Isometry3d::Identity();
  double pose_error_px = 0.0;  ///< [px] measured median noise-free static residual
  double fx = 535.4, fy = 539.2, cx = 320.1, cy = 247.6;
  int width = 640, height = 480;

  [[nodiscard]] Eigen::Index size() const { return predicted.cols(); }
  [[nodiscard]] Eigen::Vector2d project(const Eigen::Vector3d& p_c) const {
    return {fx * p_c.x() / p_c.z() + cx, fy * p_c.y() / p_c.z() + cy};
  }
};

namespace detail {

/// Uniform, normal and integer draws from the raw mt19937_64 stream (portable across libraries).
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double t = 2.0 * 3.14159265358979323846 * u2;
    spare_ = r * std::sin(t);
    has_spare_ = true;
    return r * std::cos(t);
  }
  Eigen::Vector3d unit3() {
    Eigen::Vector3d v(normal(), normal(), normal());
    return v / v.norm();
  }
  bool chance(double p) { return uniform() < p; }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

inline Eigen::Matrix3d rotation(const Eigen::Vector3d& omega) {
  const double angle = omega.norm();
  if (angle < 1e-15) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix();
}

/// T = exp(delta) * T0 with delta = (omega, tau), a left perturbation.
inline Eigen::Isometry3d perturb(const Eigen::Isometry3d& T0, const Eigen::Vector3d& omega,
                                 const Eigen::Vector3d& tau) {
  Eigen::Isometry3d d = Eigen::Isometry3d::Identity();
  d.linear() = rotation(omega);
  d.translation() = tau;
  return d * T0;
}

inline int draw_octave(Random& rng, int octaves, double scale_factor) {
  double total = 0.0;
  for (int o = 0; o < octaves; ++o) total += std::pow(scale_factor, -o);
  double u = rng.uniform() * total;
  for (int o = 0; o < octaves; ++o) {
    u -= std::pow(scale_factor, -o);
    if (u < 0.0) return o;
  }
  return octaves - 1;
}

struct Box {
  double u0, v0, u1, v1;
};

}  // namespace detail

/// Builds one scene. Throws std::invalid_argument on an impossible config.
inline Scene make_scene(const SceneConfig& config) {
  const double shares = config.person_share + config.edge_share + config.carried_share +
                        config.gross_share + config.masked_person_share;
  if (config.n_matches < 10 || shares < 0.0 || shares > 0.9 || config.pose_error_px < 0.0 ||
      config.noise_px < 0.0 || config.octaves < 1)
    throw std::invalid_argument("make_scene: invalid SceneConfig");

  detail::Random rng(config.seed);
  Scene s;
  const auto n = static_cast<Eigen::Index>(config.n_matches);
  auto count = [&](double share) {
    return static_cast<int>(std::lround(share * config.n_matches));
  };
  const int n_person = count(config.person_share);
  const int n_edge = count(config.edge_share);
  const int n_carried = count(config.carried_share);
  const int n_gross = count(config.gross_share);
  const int n_masked = count(config.masked_person_share);
  const int n_static = config.n_matches - n_person - n_edge - n_carried - n_gross - n_masked;

  // True camera motion: a translation of camera_step in a random direction and up to 1 degree of
  // rotation, like hand-held TUM sequences.
  const Eigen::Vector3d true_omega =
      rng.unit3() * rng.uniform(0.0, 1.0) * (3.14159265358979 / 180.0);
  s.T_cur_world_true =
      detail::perturb(Eigen::Isometry3d::Identity(), true_omega, rng.unit3() * config.camera_step);

  // The person: an image box at depth d0, walking mostly sideways.
  const double box_w = rng.uniform(100.0, 180.0);
  const double box_h = rng.uniform(250.0, 400.0);
  const double box_u = rng.uniform(20.0, 620.0 - box_w);
  const double box_v = rng.uniform(20.0, 460.0 - box_h);
  const detail::Box person{box_u, box_v, box_u + box_w, box_v + box_h};
  const double person_depth = rng.uniform(0.6, 1.5);
  const double speed = rng.uniform(config.person_speed_min, config.person_speed_max);
  const double heading = rng.uniform(-0.5236, 0.5236);  // within 30 degrees of sideways
  const double side = rng.chance(0.5) ? 1.0 : -1.0;
  const Eigen::Vector3d person_velocity(side * speed * std::cos(heading),
                                        0.1 * speed * rng.normal(), speed * std::sin(heading));
  // The carried object: a box at the person's side, with its own hand motion and rotation.
  const double obj_size = rng.uniform(40.0, 80.0);
  const double obj_u =
      std::clamp(side > 0 ? person.u1 - 10.0 : person.u0 - obj_size + 10.0, 5.0, 635.0 - obj_size);
  const double obj_v =
      std::clamp(rng.uniform(person.v0 + 60.0, person.v1 - 60.0), 5.0, 475.0 - obj_size);
  const detail::Box object{obj_u, obj_v, obj_u + obj_size, obj_v + obj_size};
  const double obj_depth = rng.uniform(0.45, 1.0);
  const Eigen::Vector3d obj_velocity = person_velocity + rng.unit3() * rng.uniform(0.01, 0.04);
  const Eigen::Matrix3d obj_rotation =
      detail::rotation(rng.unit3() * rng.uniform(0.0, 3.0) * (3.14159265358979 / 180.0));
  const Eigen::Vector3d obj_centre(((obj_u + obj_size / 2) - s.cx) * obj_depth / s.fx,
                                   ((obj_v + obj_size / 2) - s.cy) * obj_depth / s.fy, obj_depth);

  auto back_project = [&](double u, double v, double z) {
    return Eigen::Vector3d((u - s.cx) * z / s.fx, (v - s.cy) * z / s.fy, z);
  };
  auto in_image = [&](const Eigen::Vector2d& uv) {
    return uv.x() >= 0.0 && uv.x() < s.width && uv.y() >= 0.0 && uv.y() < s.height;
  };

  // Each match is drawn as (map point, its motion, label, flag); the pixels come later, once the
  // rough pose is known.
  struct Draw {
    Eigen::Vector3d X;
    Eigen::Vector3d X_moved;  // where the point really is at the current frame (world frame)
    Label label;
    bool flagged;
    int octave;
    Eigen::Vector2d gross_offset;
  };
  std::vector<Draw> draws;
  draws.reserve(static_cast<std::size_t>(n));
  auto person_point = [&]() {
    const double u = rng.uniform(person.u0, person.u1);
    const double v = rng.uniform(person.v0, person.v1);
    const double z = std::clamp(person_depth + 0.1 * rng.normal(), 0.6, 1.5);
    const Eigen::Vector3d X = back_project(u, v, z);
    const Eigen::Vector3d limb(rng.normal(), rng.normal(), rng.normal());
    return std::pair<Eigen::Vector3d, Eigen::Vector3d>(X,
                                                       X + person_velocity + 0.25 * speed * limb);
  };
  auto add = [&](const Eigen::Vector3d& X, const Eigen::Vector3d& X_moved, Label label,
                 bool flagged) {
    Draw d{X,
           X_moved,
           label,
           flagged,
           detail::draw_octave(rng, config.octaves, config.scale_factor),
           Eigen::Vector2d::Zero()};
    draws.push_back(d);
  };
  for (int i = 0; i < n_static; ++i) {
    const Eigen::Vector3d X =
        back_project(rng.uniform(0.0, 640.0), rng.uniform(0.0, 480.0), rng.uniform(0.5, 4.0));
    add(X, X, Label::Static, false);
  }
  for (int i = 0; i < n_person + n_masked; ++i) {
    const auto [X, X_moved] = person_point();
    add(X, X_moved, Label::DynamicPerson, i >= n_person);
  }
  for (int i = 0; i < n_edge; ++i) {
    // A corner on the left or right silhouette; its depth is the person's or the background's.
    const double u = (rng.chance(0.5) ? person.u0 : person.u1) + 3.0 * rng.normal();
    const double v = rng.uniform(person.v0, person.v1);
    const double z = rng.chance(0.5) ? person_depth : rng.uniform(person_depth + 0.5, 4.0);
    const Eigen::Vector3d X = back_project(u, v, z);
    add(X, X + rng.uniform(0.2, 1.0) * person_velocity, Label::Edge, false);
  }
  for (int i = 0; i < n_carried; ++i) {
    const Eigen::Vector3d X =
        back_project(rng.uniform(object.u0, object.u1), rng.uniform(object.v0, object.v1),
                     obj_depth + 0.02 * rng.normal());
    add(X, obj_centre + obj_rotation * (X - obj_centre) + obj_velocity, Label::CarriedObject,
        false);
  }
  for (int i = 0; i < n_gross; ++i) {
    const Eigen::Vector3d X =
        back_project(rng.uniform(0.0, 640.0), rng.uniform(0.0, 480.0), rng.uniform(0.5, 4.0));
    add(X, X, Label::GrossMismatch, false);
    const double magnitude = std::exp(rng.uniform(std::log(8.0), std::log(300.0)));
    const double angle = rng.uniform(-3.14159265358979, 3.14159265358979);
    draws.back().gross_offset = magnitude * Eigen::Vector2d(std::cos(angle), std::sin(angle));
  }

  // Rough pose: a random direction of rotation and translation error, scaled so that the median
  // noise-free static residual is pose_error_px (two secant steps absorb the slight nonlinearity).
  const Eigen::Vector3d err_omega = rng.unit3() * rng.uniform(0.3, 1.0) / s.fx;
  const Eigen::Vector3d err_tau = rng.unit3() * rng.uniform(0.0, 1.0) * 2.0 / s.fx;
  auto median_static_residual = [&](double scale) {
    const Eigen::Isometry3d T =
        detail::perturb(s.T_cur_world_true, scale * err_omega, scale * err_tau);
    std::vector<double> r;
    for (const Draw& d : draws) {
      if (d.label != Label::Static) continue;
      r.push_back((s.project(T * d.X) - s.project(s.T_cur_world_true * d.X)).norm());
    }
    std::nth_element(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(r.size() / 2), r.end());
    return r[r.size() / 2];
  };
  double scale = 0.0;
  if (config.pose_error_px > 0.0) {
    scale = config.pose_error_px / median_static_residual(1.0);
    for (int it = 0; it < 2; ++it) scale *= config.pose_error_px / median_static_residual(scale);
  }
  s.T_cur_world_rough = detail::perturb(s.T_cur_world_true, scale * err_omega, scale * err_tau);
  s.pose_error_px = config.pose_error_px > 0.0 ? median_static_residual(scale) : 0.0;

  // Pixels; a draw whose pixels leave the image is moved to a fresh spot of the same kind.
  s.predicted.resize(2, n);
  s.observed.resize(2, n);
  s.points_world.resize(3, n);
  s.sigma.resize(n);
  s.on_dynamic_mask.resize(n);
  s.octave.resize(static_cast<std::size_t>(n));
  s.label.resize(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    Draw d = draws[static_cast<std::size_t>(i)];
    Eigen::Vector2d predicted, observed;
    for (int attempt = 0;; ++attempt) {
      const Eigen::Vector3d p_rough = s.T_cur_world_rough * d.X;
      const Eigen::Vector3d p_true = s.T_cur_world_true * d.X_moved;
      const double sigma = std::pow(config.scale_factor, d.octave);
      predicted = s.project(p_rough);
      observed = s.project(p_true) + d.gross_offset +
                 config.noise_px * sigma * Eigen::Vector2d(rng.normal(), rng.normal());
      if ((p_rough.z() > 0.1 && p_true.z() > 0.1 && in_image(predicted) && in_image(observed)) ||
          attempt >= 50)
        break;
      // Nudge the point towards the image centre (keeps its label and motion).
      const Eigen::Vector3d shift = back_project(320.0, 240.0, d.X.z()) - d.X;
      d.X += 0.2 * shift;
      d.X_moved += 0.2 * shift;
      if (d.label == Label::GrossMismatch) d.gross_offset *= 0.7;
    }
    s.predicted.col(i) = predicted;
    s.observed.col(i) = observed;
    s.points_world.col(i) = d.X;
    s.octave[static_cast<std::size_t>(i)] = d.octave;
    s.sigma(i) = std::pow(config.scale_factor, d.octave);
    s.on_dynamic_mask(i) = d.flagged;
    s.label[static_cast<std::size_t>(i)] = d.label;
  }
  return s;
}

/// Survival counts of one screened scene, per label: kept[label] of total[label].
struct Tally {
  long kept[kLabelCount] = {0, 0, 0, 0, 0};
  long total[kLabelCount] = {0, 0, 0, 0, 0};

  void add(Label label, bool kept_match) {
    const auto l = static_cast<int>(label);
    total[l] += 1;
    kept[l] += kept_match ? 1 : 0;
  }
  /// Adds a whole mask over a scene (mask[i] true = the screen kept match i).
  template <class Mask>
  void add_scene(const Scene& scene, const Mask& kept_mask) {
    for (Eigen::Index i = 0; i < scene.size(); ++i)
      add(scene.label[static_cast<std::size_t>(i)], static_cast<bool>(kept_mask(i)));
  }
  Tally& operator+=(const Tally& o) {
    for (int l = 0; l < kLabelCount; ++l) {
      kept[l] += o.kept[l];
      total[l] += o.total[l];
    }
    return *this;
  }
  /// Share of static matches dropped, in [0, 1] (0 when there are none).
  [[nodiscard]] double static_loss() const {
    const long t = total[0];
    return t > 0 ? 1.0 - static_cast<double>(kept[0]) / static_cast<double>(t) : 0.0;
  }
  /// Share of moving matches (person, edge, carried object) kept, in [0, 1] (0 when none).
  [[nodiscard]] double dynamic_survival() const {
    long k = 0, t = 0;
    for (int l = 1; l <= 3; ++l) {
      k += kept[l];
      t += total[l];
    }
    return t > 0 ? static_cast<double>(k) / static_cast<double>(t) : 0.0;
  }
  /// Share of matches with this label kept (0 when there are none).
  [[nodiscard]] double survival(Label label) const {
    const auto l = static_cast<int>(label);
    return total[l] > 0 ? static_cast<double>(kept[l]) / static_cast<double>(total[l]) : 0.0;
  }
};

}  // namespace hbos_test
