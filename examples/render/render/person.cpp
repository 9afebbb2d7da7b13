#include "render/person.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

namespace hbos::render {
namespace {

constexpr float kDeg = 3.14159265f / 180.f;

// Body dimensions [m] (an adult of ~1.76 m).
constexpr float kHipStand = 0.92f, kHipSeated = 0.53f;
constexpr float kThighLen = 0.45f, kShinLen = 0.42f, kUpperArmLen = 0.28f, kForearmLen = 0.25f;
constexpr float kHipX = 0.10f, kShoulderX = 0.25f, kShoulderZ = 0.55f;

using Affine = Eigen::Affine3f;
Affine T(float x, float y, float z) { return Affine(Eigen::Translation3f(x, y, z)); }
Affine Rx(float a) { return Affine(Eigen::AngleAxisf(a, Eigen::Vector3f::UnitX())); }
Affine Rz(float a) { return Affine(Eigen::AngleAxisf(a, Eigen::Vector3f::UnitZ())); }

}  // namespace

PersonModel::PersonModel(GlRenderer& gl, const TextureLibrary& tex, int look, float height_scale)
    : scale_(height_scale) {
  auto box = [&](Part p, float wx, float dy, float hz, const std::array<UvRect, 6>& uv) {
    std::vector<Vertex> v;
    add_box(v, Eigen::Vector3f(wx / 2, dy / 2, hz / 2), uv);
    mesh_[p] = gl.add_mesh(v);
  };
  box(kPelvis, 0.34f, 0.20f, 0.16f, whole_texture_on_every_face());
  box(kTorso, 0.40f, 0.22f, 0.52f, whole_texture_on_every_face());
  box(kNeck, 0.10f, 0.10f, 0.08f, whole_texture_on_every_face());
  box(kUpperArm, 0.09f, 0.09f, kUpperArmLen, whole_texture_on_every_face());
  box(kForearm, 0.08f, 0.08f, kForearmLen, whole_texture_on_every_face());
  box(kHand, 0.07f, 0.04f, 0.10f, whole_texture_on_every_face());
  box(kThigh, 0.15f, 0.16f, kThighLen, whole_texture_on_every_face());
  box(kShin, 0.12f, 0.12f, kShinLen, whole_texture_on_every_face());
  box(kFoot, 0.10f, 0.24f, 0.07f, whole_texture_on_every_face());
  box(kCarried, 0.40f, 0.26f, 0.24f, whole_texture_on_every_face());

  // Head: the face on the front (+y), hair on every other face, from one two-region atlas.
  float split = 0.5f;
  const cv::Mat head_atlas = TextureLibrary::side_by_side(
      tex.get("face"), tex.get(look == 0 ? "hair" : "dark_hair"), split);
  std::array<UvRect, 6> head_uv;
  head_uv.fill(UvRect{split, 0.f, 1.f, 1.f});
  head_uv[2] = UvRect{0.f, 0.f, split, 1.f};
  box(kHead, 0.19f, 0.22f, 0.24f, head_uv);
  tex_[kHead] = gl.add_texture(head_atlas, false);

  auto t = [&](const char* name) { return gl.add_texture(tex.get(name), false); };
  const int skin = t("skin");
  tex_[kNeck] = tex_[kHand] = tex_[kForearm] = skin;
  tex_[kFoot] = t("shoe");
  tex_[kCarried] = t("carried");
  if (look == 1) {
    tex_[kTorso] = tex_[kUpperArm] = t("black_tee");
    tex_[kPelvis] = tex_[kThigh] = t("camo");
    tex_[kShin] = t("shin");
  } else {
    cv::Mat shirt = tex.get("plaid_shirt");
    if (look == 2) cv::flip(shirt, shirt, 1);
    tex_[kTorso] = tex_[kUpperArm] = gl.add_texture(shirt, false);
    tex_[kPelvis] = tex_[kThigh] = tex_[kShin] = t(look == 2 ? "black_tee" : "jeans");
    tint_ = look == 2 ? 0.8f : 1.f;
  }
}

void PersonModel::draw(const BodyState& s, int id, int carried_id,
                       std::vector<DrawItem>& out) const {
  const auto w = static_cast<float>(s.walking);
  const auto phi = static_cast<float>(s.gait_phase);
  const auto sit = static_cast<float>(s.sit);
  const float hip_z = kHipStand + (kHipSeated - kHipStand) * sit + 0.015f * w * std::cos(2 * phi);
  const Affine root = T(static_cast<float>(s.position.x()), static_cast<float>(s.position.y()), 0) *
                      Rz(static_cast<float>(s.yaw)) * Affine(Eigen::Scaling(scale_));
  auto put = [&](Part p, const Affine& a, int object_id) {
    DrawItem d;
    d.mesh = mesh_[p];
    d.texture = tex_[p];
    d.model = a.matrix();
    d.object_id = object_id;
    d.tint = p == kCarried ? 1.f : tint_;
    out.push_back(d);
  };
  put(kPelvis, root * T(0, 0, hip_z + 0.02f), id);
  put(kTorso, root * T(0, 0, hip_z + 0.34f), id);
  put(kNeck, root * T(0, 0, hip_z + 0.63f), id);
  put(kHead, root * T(0, 0, hip_z + 0.78f) * Rz(static_cast<float>(s.head_yaw)), id);

  // Legs: the swing leg's knee bends while its hip swings forward (cos phi > 0 for the left).
  for (int side = -1; side <= 1; side += 2) {
    const float sgn = side < 0 ? 1.f : -1.f;  // left leg leads the phase
    const float hip = 90.f * kDeg * sit + 25.f * kDeg * w * sgn * std::sin(phi);
    const float knee = 90.f * kDeg * sit + 40.f * kDeg * w * std::max(0.f, sgn * std::cos(phi));
    const Affine thigh = root * T(static_cast<float>(side) * kHipX, 0, hip_z) * Rx(hip);
    put(kThigh, thigh * T(0, 0, -kThighLen / 2), id);
    const Affine shin = thigh * T(0, 0, -kThighLen) * Rx(-knee);
    put(kShin, shin * T(0, 0, -kShinLen / 2), id);
    // The foot stays level with the floor when the shin is vertical.
    put(kFoot, shin * T(0, 0, -kShinLen) * Rx(knee - hip) * T(0, 0.05f, -0.035f), id);
  }
  // Arms: opposite to the legs when walking; resting on the lap when seated; holding the box.
  const bool carrying = carried_id > 0;
  for (int side = -1; side <= 1; side += 2) {
    const float sgn = side < 0 ? -1.f : 1.f;
    float shoulder = 20.f * kDeg * w * sgn * std::sin(phi) + 25.f * kDeg * sit;
    float elbow = (12.f + 10.f * w) * kDeg + 45.f * kDeg * sit;
    if (carrying) {
      shoulder = 30.f * kDeg;
      elbow = 70.f * kDeg;
    }
    const Affine upper =
        root * T(static_cast<float>(side) * kShoulderX, 0, hip_z + kShoulderZ) * Rx(shoulder);
    put(kUpperArm, upper * T(0, 0, -kUpperArmLen / 2), id);
    const Affine fore = upper * T(0, 0, -kUpperArmLen) * Rx(elbow);
    put(kForearm, fore * T(0, 0, -kForearmLen / 2), id);
    put(kHand, fore * T(0, 0, -kForearmLen - 0.05f), id);
  }
  if (carrying) put(kCarried, root * T(0, 0.36f, hip_z + 0.33f), carried_id);
}

}  // namespace hbos::render
