#pragma once
/// \file
/// Triangle meshes of textured boxes: the only primitive of the scene (walls, furniture, body
/// parts, the carried object are all boxes with photographic texture on their faces).

#include <array>
#include <vector>

#include <Eigen/Core>

namespace hbos::render {

/// One vertex as the GPU reads it (interleaved floats).
struct Vertex {
  float px, py, pz;  ///< [m] position in the mesh's own frame
  float nx, ny, nz;  ///< unit normal
  float u, v;        ///< texture coordinate (0..1 across the texture; > 1 tiles)
};

/// A rectangle of a texture, in texture coordinates (u right, v down, 0..1 across the image);
/// `repeat_u/v` > 1 tiles it (only sensible for a whole-image region with repeat wrapping).
struct UvRect {
  float u0 = 0.f, v0 = 0.f, u1 = 1.f, v1 = 1.f;
};

/// The whole texture on each of a box's six faces.
inline std::array<UvRect, 6> whole_texture_on_every_face() {
  std::array<UvRect, 6> r;
  r.fill(UvRect{});
  return r;
}

/// Builds a box centred on the origin with half sizes `half` [m]. Face order: +x, -x, +y, -y,
/// +z, -z. Each face gets its own rectangle of the texture, mapped upright: v runs down the face
/// (towards -z on side faces; towards -y on the top and bottom faces).
void add_box(std::vector<Vertex>& out, const Eigen::Vector3f& half,
             const std::array<UvRect, 6>& faces);

/// An axis-aligned box from `lo` to `hi` [m] whose faces tile the texture once per `tile` metres
/// (a wall or a floor): the face regions are in metres / tile, to be drawn with repeat wrapping.
void add_tiled_box(std::vector<Vertex>& out, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi,
                   float tile_u, float tile_v);

}  // namespace hbos::render
