#pragma once
/// \file
/// Rasterisation with Mesa's offscreen OpenGL (OSMesa, llvmpipe on the CPU): textured triangle
/// meshes in, colour, noise-free depth, world position, object id and incidence angle out.
///
/// Threading: one GlRenderer owns one OpenGL context; use it from the thread that created it.
/// Several may exist on one thread: each call makes its own context current.

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "render/camera.hpp"
#include "render/mesh.hpp"

namespace hbos::render {

/// Everything one rendered view says, before any sensor noise.
struct RenderedView {
  cv::Mat bgr;            ///< CV_8UC3, the shaded texture colour
  cv::Mat depth;          ///< CV_32F [m] camera z of the visible surface; 0 where nothing was hit
  cv::Mat world;          ///< CV_32FC3 [m] world position of the visible surface (room frame)
  cv::Mat object_id;      ///< CV_8U: 0 static background, 1..k people, k+1.. carried objects
  cv::Mat cos_incidence;  ///< CV_32F |cos| of the angle between viewing ray and surface normal
};

/// A mesh uploaded once; drawn any number of times with its own model matrix.
struct MeshHandle {
  unsigned vao = 0, vbo = 0;
  int vertex_count = 0;
};

/// One draw: a mesh, a texture, a placement and an object id.
struct DrawItem {
  int mesh = 0;                                         ///< index from GlRenderer::add_mesh
  int texture = 0;                                      ///< index from GlRenderer::add_texture
  Eigen::Matrix4f model = Eigen::Matrix4f::Identity();  ///< mesh frame -> world [m]
  int object_id = 0;                                    ///< 0..255
  float tint = 1.f;  ///< brightness factor (variety between people)
};

/// Owns the OSMesa context, the shader program, the offscreen framebuffer, meshes and textures.
class GlRenderer {
 public:
  /// Creates a core-profile context (3.3) and a framebuffer of the camera's size.
  /// \throws std::runtime_error if OSMesa cannot create the context or the framebuffer.
  explicit GlRenderer(const Intrinsics& K);
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  /// Uploads an 8-bit BGR image with mipmaps; `repeat` selects repeat (tiling) or clamp wrapping.
  int add_texture(const cv::Mat& bgr, bool repeat);
  /// Uploads a mesh (triangles).
  int add_mesh(const std::vector<Vertex>& vertices);

  /// Renders the items seen by a camera at `T_world_camera` and reads everything back.
  RenderedView render(const Pose& T_world_camera, const std::vector<DrawItem>& items);

  /// The OpenGL renderer string (for scenario.json: which rasteriser produced the bytes).
  std::string gl_renderer_name() const;

 private:
  void make_current();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The OpenGL projection matrix that reproduces the pinhole `K` exactly (OpenCV pixel centres at
/// integer coordinates, image row 0 at the top after the read-back flip).
Eigen::Matrix4f projection_matrix(const Intrinsics& K, float near_m, float far_m);

}  // namespace hbos::render
