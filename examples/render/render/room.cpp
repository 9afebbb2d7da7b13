#include "render/room.hpp"

namespace hbos::render {

std::vector<DrawItem> build_room(GlRenderer& gl, const TextureLibrary& tex, const RoomLayout& r) {
  std::vector<DrawItem> items;
  auto item = [&](const std::vector<Vertex>& v, int texture) {
    DrawItem d;
    d.mesh = gl.add_mesh(v);
    d.texture = texture;
    items.push_back(d);
  };
  auto tiled = [&](const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, const char* name, float tu,
                   float tv) {
    std::vector<Vertex> v;
    add_tiled_box(v, lo, hi, tu, tv);
    item(v, gl.add_texture(tex.get(name), true));
  };
  // A box from lo to hi with one image on every face (furniture).
  auto solid = [&](const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, int texture) {
    std::vector<Vertex> v;
    std::vector<Vertex> local;
    add_box(local, 0.5f * (hi - lo), whole_texture_on_every_face());
    const Eigen::Vector3f mid = 0.5f * (hi + lo);
    for (Vertex x : local) {
      x.px += mid.x();
      x.py += mid.y();
      x.pz += mid.z();
      v.push_back(x);
    }
    item(v, texture);
  };
  const float t = 0.05f;  // [m] wall thickness
  // Murals: each wall carries one whole photograph, 4:3, tiled at 4.0 m x 3.0 m.
  tiled({r.x_min, r.y_min, -t}, {r.x_max, r.y_max, 0.f}, "floor", 1.5f, 0.6f);
  tiled({r.x_min, r.y_min, r.height}, {r.x_max, r.y_max, r.height + t}, "ceiling", 3.0f, 0.3f);
  tiled({r.x_min, r.y_max, 0.f}, {r.x_max, r.y_max + t, r.height}, "wall_front", 4.0f, 3.0f);
  tiled({r.x_min, r.y_min - t, 0.f}, {r.x_max, r.y_min, r.height}, "wall_back", 4.0f, 3.0f);
  tiled({r.x_min - t, r.y_min, 0.f}, {r.x_min, r.y_max, r.height}, "wall_left", 4.0f, 3.0f);
  tiled({r.x_max, r.y_min, 0.f}, {r.x_max + t, r.y_max, r.height}, "wall_right", 4.0f, 3.0f);

  // The desk: a top-down photo of a cluttered desk (fr1) as its top, wooden sides, dark legs.
  const int desk_top = gl.add_texture(tex.get("desk_top"), false);
  const int desk_side = gl.add_texture(tex.get("desk_side"), false);
  const int dark = gl.add_texture(tex.get("dark"), false);
  {
    std::vector<Vertex> v;
    std::array<UvRect, 6> uv = whole_texture_on_every_face();
    add_box(v, Eigen::Vector3f(0.8f, 0.4f, 0.02f), uv);
    for (Vertex& x : v) x.pz += 0.73f;
    // Top face with the desk photo, side faces with the edge crop: two draws of one geometry.
    std::vector<Vertex> top(v.begin() + 24, v.begin() + 30);
    std::vector<Vertex> sides(v.begin(), v.begin() + 24);
    item(top, desk_top);
    item(sides, desk_side);
  }
  for (float sx : {-0.75f, 0.72f}) {
    for (float sy : {-0.35f, 0.32f}) solid({sx, sy, 0.f}, {sx + 0.04f, sy + 0.04f, 0.71f}, dark);
  }
  // A modesty panel under the desk's far edge (the fr3 desks have one), and the monitor.
  solid({-0.75f, 0.35f, 0.15f}, {0.75f, 0.38f, 0.71f}, gl.add_texture(tex.get("partition"), false));
  solid({-0.28f, 0.12f, 0.80f}, {0.28f, 0.16f, 1.15f}, gl.add_texture(tex.get("monitor"), false));
  solid({-0.04f, 0.13f, 0.75f}, {0.04f, 0.17f, 0.80f}, dark);

  // A second table against the front wall, a shelf on the right, a box on the floor.
  solid({-3.0f, 1.0f, 0.70f}, {-1.6f, 1.65f, 0.74f}, gl.add_texture(tex.get("table2_top"), false));
  solid({-2.95f, 1.05f, 0.f}, {-2.9f, 1.6f, 0.70f}, dark);
  solid({-1.7f, 1.05f, 0.f}, {-1.65f, 1.6f, 0.70f}, dark);
  solid({1.7f, 1.25f, 0.f}, {2.6f, 1.65f, 1.4f}, gl.add_texture(tex.get("shelf"), false));
  solid({-2.2f, -0.6f, 0.f}, {-1.7f, -0.2f, 0.35f}, gl.add_texture(tex.get("cardboard"), false));
  // Chairs: seat, back (on the far side: the sitter faces -y), one central leg.
  const int chair = gl.add_texture(tex.get("chair"), false);
  for (const Eigen::Vector2d& c : {r.chair_left, r.chair_right}) {
    const auto cx = static_cast<float>(c.x());
    const auto cy = static_cast<float>(c.y());
    solid({cx - 0.22f, cy - 0.22f, 0.40f}, {cx + 0.22f, cy + 0.22f, 0.45f}, chair);
    solid({cx - 0.22f, cy + 0.22f, 0.50f}, {cx + 0.22f, cy + 0.26f, 0.95f}, chair);
    solid({cx - 0.03f, cy - 0.03f, 0.f}, {cx + 0.03f, cy + 0.03f, 0.40f}, dark);
  }
  return items;
}

}  // namespace hbos::render
