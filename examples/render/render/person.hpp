#pragma once
/// \file
/// A person as an articulated body of textured boxes (pelvis, torso, neck, head, upper arms,
/// forearms, hands, thighs, shins, feet) dressed in real clothing cut from the fr3/walking_xyz
/// people: walking swings the arms and legs, sitting folds hips and knees, carrying holds a box.

#include <vector>

#include "render/gl_renderer.hpp"
#include "render/script.hpp"
#include "render/textures.hpp"

namespace hbos::render {

/// One person's appearance and GPU meshes (built once, posed every frame).
class PersonModel {
 public:
  /// `look` 0, 1, 2 picks one of three outfits (plaid shirt and jeans; black T-shirt and camo
  /// shorts; a darker plaid with dark trousers); `height_scale` ~1 varies the body size.
  PersonModel(GlRenderer& gl, const TextureLibrary& tex, int look, float height_scale);

  /// Appends the draw items of the body in state `s` with object id `id`; when `carried_id` > 0
  /// the arms hold a box in front of the body, drawn with that id.
  void draw(const BodyState& s, int id, int carried_id, std::vector<DrawItem>& out) const;

 private:
  enum Part {
    kPelvis,
    kTorso,
    kNeck,
    kHead,
    kUpperArm,
    kForearm,
    kHand,
    kThigh,
    kShin,
    kFoot,
    kCarried,
    kPartCount
  };
  int mesh_[kPartCount] = {};
  int tex_[kPartCount] = {};
  float tint_ = 1.f;
  float scale_ = 1.f;
};

}  // namespace hbos::render
