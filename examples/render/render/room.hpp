#pragma once
/// \file
/// The static room: floor, four walls and a ceiling, the desk the fr3 camera looks at (with a
/// monitor), a second table, a shelf, two chairs, a cardboard box. Object id 0 throughout.
///
/// Room frame: z up, floor at z = 0, the main desk centred on the origin, its long side along x;
/// the camera path is placed on the -y side looking along +y (see room_offset).

#include <vector>

#include <Eigen/Core>

#include "render/gl_renderer.hpp"
#include "render/textures.hpp"

namespace hbos::render {

/// Room extent and furniture positions [m] (the people's scripts use the chairs).
struct RoomLayout {
  float x_min = -3.5f, x_max = 3.5f;        ///< [m] side walls
  float y_min = -4.5f, y_max = 2.5f;        ///< [m] back wall (behind the camera), front wall
  float height = 3.0f;                      ///< [m] ceiling
  Eigen::Vector2d chair_left{-0.40, 0.95};  ///< [m] seat centre behind the desk (faces -y)
  Eigen::Vector2d chair_right{0.45, 0.95};  ///< [m]
};

/// Uploads the room's meshes and textures; returns its draw items (all object id 0).
std::vector<DrawItem> build_room(GlRenderer& gl, const TextureLibrary& tex, const RoomLayout& room);

}  // namespace hbos::render
