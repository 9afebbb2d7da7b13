#include "render/mesh.hpp"

namespace hbos::render {
namespace {

// One face as a quad: its centre offset, its right (u) and down (v) axes, all scaled by the
// half sizes, and its outward normal.
struct Face {
  Eigen::Vector3f normal, right, down;
};

const std::array<Face, 6>& faces() {
  static const std::array<Face, 6> f = {{
      {{1, 0, 0}, {0, 1, 0}, {0, 0, -1}},    // +x: seen from +x, +y is to the right
      {{-1, 0, 0}, {0, -1, 0}, {0, 0, -1}},  // -x
      {{0, 1, 0}, {-1, 0, 0}, {0, 0, -1}},   // +y
      {{0, -1, 0}, {1, 0, 0}, {0, 0, -1}},   // -y (the front of a body: +x on the right)
      {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}},    // +z (top)
      {{0, 0, -1}, {1, 0, 0}, {0, 1, 0}},    // -z (bottom)
  }};
  return f;
}

void add_quad(std::vector<Vertex>& out, const Eigen::Vector3f& centre, const Eigen::Vector3f& right,
              const Eigen::Vector3f& down, const Eigen::Vector3f& n, const UvRect& r) {
  const Eigen::Vector3f c00 = centre - right - down;  // top-left
  const Eigen::Vector3f c10 = centre + right - down;  // top-right
  const Eigen::Vector3f c01 = centre - right + down;  // bottom-left
  const Eigen::Vector3f c11 = centre + right + down;  // bottom-right
  auto v = [&](const Eigen::Vector3f& p, float u, float vv) {
    out.push_back(Vertex{p.x(), p.y(), p.z(), n.x(), n.y(), n.z(), u, vv});
  };
  // Counter-clockwise seen from outside (along -n).
  v(c00, r.u0, r.v0);
  v(c01, r.u0, r.v1);
  v(c11, r.u1, r.v1);
  v(c00, r.u0, r.v0);
  v(c11, r.u1, r.v1);
  v(c10, r.u1, r.v0);
}

}  // namespace

void add_box(std::vector<Vertex>& out, const Eigen::Vector3f& half,
             const std::array<UvRect, 6>& rects) {
  for (std::size_t i = 0; i < 6; ++i) {
    const Face& f = faces()[i];
    const Eigen::Vector3f centre = f.normal.cwiseProduct(half);
    add_quad(out, centre, f.right.cwiseProduct(half), f.down.cwiseProduct(half), f.normal,
             rects[i]);
  }
}

void add_tiled_box(std::vector<Vertex>& out, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi,
                   float tile_u, float tile_v) {
  const Eigen::Vector3f half = 0.5f * (hi - lo);
  const Eigen::Vector3f mid = 0.5f * (hi + lo);
  for (std::size_t i = 0; i < 6; ++i) {
    const Face& f = faces()[i];
    const Eigen::Vector3f right = f.right.cwiseProduct(half);
    const Eigen::Vector3f down = f.down.cwiseProduct(half);
    const float w = 2.f * right.norm() / tile_u;
    const float h = 2.f * down.norm() / tile_v;
    add_quad(out, mid + f.normal.cwiseProduct(half), right, down, f.normal, UvRect{0.f, 0.f, w, h});
  }
}

}  // namespace hbos::render
