#include "render/gl_renderer.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <stdexcept>

namespace hbos::render {
namespace {

constexpr float kNear = 0.05f;  // [m]
constexpr float kFar = 50.f;    // [m]

const char* const kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_proj;
uniform mat3 u_normal_matrix;
out vec3 v_world;
out vec3 v_normal;
out vec2 v_uv;
out float v_zcam;
void main() {
  vec4 w = u_model * vec4(a_pos, 1.0);
  vec4 e = u_view * w;
  v_world = w.xyz;
  v_normal = u_normal_matrix * a_normal;
  v_uv = a_uv;
  v_zcam = -e.z;
  gl_Position = u_proj * e;
}
)";

// Outputs: colour; world position + camera z; object id + |cos incidence|.
const char* const kFragmentShader = R"(#version 330 core
in vec3 v_world;
in vec3 v_normal;
in vec2 v_uv;
in float v_zcam;
uniform sampler2D u_tex;
uniform vec3 u_camera_centre;
uniform float u_object_id;
uniform float u_tint;
layout(location = 0) out vec4 o_colour;
layout(location = 1) out vec4 o_geometry;
layout(location = 2) out vec4 o_label;
void main() {
  vec3 n = normalize(v_normal);
  vec3 to_cam = normalize(u_camera_centre - v_world);
  // Photographs carry their own lighting; a soft key light from above only separates faces.
  float light = 0.78 + 0.22 * max(dot(n, normalize(vec3(0.3, -0.5, 0.8))), 0.0);
  vec3 c = texture(u_tex, v_uv).rgb * light * u_tint;
  o_colour = vec4(clamp(c, 0.0, 1.0), 1.0);
  o_geometry = vec4(v_world, v_zcam);
  o_label = vec4(u_object_id, abs(dot(n, to_cam)), 0.0, 1.0);
}
)";

unsigned compile(GLenum type, const char* src) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("OpenGL shader compilation failed: ") + log);
  }
  return s;
}

}  // namespace

Eigen::Matrix4f projection_matrix(const Intrinsics& K, float n, float f) {
  const auto W = static_cast<float>(K.width);
  const auto H = static_cast<float>(K.height);
  const auto fx = static_cast<float>(K.fx);
  const auto fy = static_cast<float>(K.fy);
  const auto cx = static_cast<float>(K.cx);
  const auto cy = static_cast<float>(K.cy);
  // Eye frame = camera frame with y and z negated. OpenGL pixel centres are at +0.5, so
  // u_gl = u_cv + 0.5; the read-back is flipped, so v_gl = H - (v_cv + 0.5).
  Eigen::Matrix4f P = Eigen::Matrix4f::Zero();
  P(0, 0) = 2.f * fx / W;
  P(0, 2) = 1.f - 2.f * (cx + 0.5f) / W;
  P(1, 1) = 2.f * fy / H;
  P(1, 2) = 2.f * (cy + 0.5f) / H - 1.f;
  P(2, 2) = -(f + n) / (f - n);
  P(2, 3) = -2.f * f * n / (f - n);
  P(3, 2) = -1.f;
  return P;
}

struct GlRenderer::Impl {
  Intrinsics K;
  OSMesaContext ctx = nullptr;
  std::vector<unsigned char> osmesa_buffer;
  GLuint program = 0, fbo = 0, depth_rb = 0;
  GLuint colour_tex[3] = {0, 0, 0};
  std::vector<MeshHandle> meshes;
  std::vector<GLuint> textures;
  GLint loc_model = 0, loc_view = 0, loc_proj = 0, loc_nm = 0, loc_cam = 0, loc_id = 0,
        loc_tint = 0, loc_tex = 0;
  std::vector<unsigned char> rgba;
  std::vector<float> geometry, label;
};

GlRenderer::GlRenderer(const Intrinsics& K) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.K = K;
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         24,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         3,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         3,
                         0};
  m.ctx = OSMesaCreateContextAttribs(attribs, nullptr);
  if (m.ctx == nullptr) {
    throw std::runtime_error("OSMesa could not create an OpenGL 3.3 core context");
  }
  m.osmesa_buffer.resize(static_cast<std::size_t>(K.width) * static_cast<std::size_t>(K.height) *
                         4);
  if (!OSMesaMakeCurrent(m.ctx, m.osmesa_buffer.data(), GL_UNSIGNED_BYTE, K.width, K.height)) {
    OSMesaDestroyContext(m.ctx);
    throw std::runtime_error("OSMesaMakeCurrent failed");
  }
  const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader);
  const GLuint fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  m.program = glCreateProgram();
  glAttachShader(m.program, vs);
  glAttachShader(m.program, fs);
  glLinkProgram(m.program);
  GLint ok = 0;
  glGetProgramiv(m.program, GL_LINK_STATUS, &ok);
  glDeleteShader(vs);
  glDeleteShader(fs);
  if (!ok) throw std::runtime_error("OpenGL program link failed");
  m.loc_model = glGetUniformLocation(m.program, "u_model");
  m.loc_view = glGetUniformLocation(m.program, "u_view");
  m.loc_proj = glGetUniformLocation(m.program, "u_proj");
  m.loc_nm = glGetUniformLocation(m.program, "u_normal_matrix");
  m.loc_cam = glGetUniformLocation(m.program, "u_camera_centre");
  m.loc_id = glGetUniformLocation(m.program, "u_object_id");
  m.loc_tint = glGetUniformLocation(m.program, "u_tint");
  m.loc_tex = glGetUniformLocation(m.program, "u_tex");

  // Offscreen framebuffer: RGBA8 colour, two RGBA32F attachments, a 24-bit depth buffer.
  glGenFramebuffers(1, &m.fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, m.fbo);
  glGenTextures(3, m.colour_tex);
  const GLint formats[3] = {GL_RGBA8, GL_RGBA32F, GL_RGBA32F};
  const GLenum types[3] = {GL_UNSIGNED_BYTE, GL_FLOAT, GL_FLOAT};
  for (int i = 0; i < 3; ++i) {
    glBindTexture(GL_TEXTURE_2D, m.colour_tex[i]);
    glTexImage2D(GL_TEXTURE_2D, 0, formats[i], K.width, K.height, 0, GL_RGBA, types[i], nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i),
                           GL_TEXTURE_2D, m.colour_tex[i], 0);
  }
  glGenRenderbuffers(1, &m.depth_rb);
  glBindRenderbuffer(GL_RENDERBUFFER, m.depth_rb);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, K.width, K.height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m.depth_rb);
  const GLenum bufs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
  glDrawBuffers(3, bufs);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error("OpenGL framebuffer is incomplete");
  }
  glViewport(0, 0, K.width, K.height);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  const std::size_t n = static_cast<std::size_t>(K.width) * static_cast<std::size_t>(K.height);
  m.rgba.resize(n * 4);
  m.geometry.resize(n * 4);
  m.label.resize(n * 4);
}

GlRenderer::~GlRenderer() {
  Impl& m = *impl_;
  OSMesaMakeCurrent(m.ctx, m.osmesa_buffer.data(), GL_UNSIGNED_BYTE, m.K.width, m.K.height);
  for (auto& h : m.meshes) {
    glDeleteBuffers(1, &h.vbo);
    glDeleteVertexArrays(1, &h.vao);
  }
  if (!m.textures.empty())
    glDeleteTextures(static_cast<GLsizei>(m.textures.size()), m.textures.data());
  glDeleteTextures(3, m.colour_tex);
  glDeleteRenderbuffers(1, &m.depth_rb);
  glDeleteFramebuffers(1, &m.fbo);
  glDeleteProgram(m.program);
  OSMesaDestroyContext(m.ctx);
}

void GlRenderer::make_current() {
  Impl& m = *impl_;
  if (OSMesaGetCurrentContext() != m.ctx &&
      !OSMesaMakeCurrent(m.ctx, m.osmesa_buffer.data(), GL_UNSIGNED_BYTE, m.K.width, m.K.height)) {
    throw std::runtime_error("OSMesaMakeCurrent failed");
  }
}

int GlRenderer::add_texture(const cv::Mat& bgr, bool repeat) {
  make_current();
  if (bgr.empty() || bgr.type() != CV_8UC3) throw std::runtime_error("texture must be 8-bit BGR");
  cv::Mat img = bgr.isContinuous() ? bgr : bgr.clone();
  GLuint t = 0;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_2D, t);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, img.cols, img.rows, 0, GL_BGR, GL_UNSIGNED_BYTE,
               img.data);
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  const GLint wrap = repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
  glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_ANISOTROPY_EXT, 4.f);
  impl_->textures.push_back(t);
  return static_cast<int>(impl_->textures.size()) - 1;
}

int GlRenderer::add_mesh(const std::vector<Vertex>& vertices) {
  make_current();
  MeshHandle h;
  glGenVertexArrays(1, &h.vao);
  glBindVertexArray(h.vao);
  glGenBuffers(1, &h.vbo);
  glBindBuffer(GL_ARRAY_BUFFER, h.vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(Vertex)),
               vertices.data(), GL_STATIC_DRAW);
  const auto stride = static_cast<GLsizei>(sizeof(Vertex));
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(0));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<void*>(3 * sizeof(float)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<void*>(6 * sizeof(float)));
  glBindVertexArray(0);
  h.vertex_count = static_cast<int>(vertices.size());
  impl_->meshes.push_back(h);
  return static_cast<int>(impl_->meshes.size()) - 1;
}

std::string GlRenderer::gl_renderer_name() const {
  const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(r ? r : "?") + " / " + (v ? v : "?");
}

RenderedView GlRenderer::render(const Pose& T_wc, const std::vector<DrawItem>& items) {
  Impl& m = *impl_;
  const int W = m.K.width, H = m.K.height;
  // Several renderers may live on one thread (a test compares two): make ours current.
  make_current();
  glBindFramebuffer(GL_FRAMEBUFFER, m.fbo);
  const float zero4[4] = {0.f, 0.f, 0.f, 0.f};
  glClearBufferfv(GL_COLOR, 0, zero4);
  glClearBufferfv(GL_COLOR, 1, zero4);
  glClearBufferfv(GL_COLOR, 2, zero4);
  glClear(GL_DEPTH_BUFFER_BIT);
  glUseProgram(m.program);

  Eigen::Matrix4d flip = Eigen::Matrix4d::Identity();
  flip(1, 1) = -1.0;
  flip(2, 2) = -1.0;
  const Eigen::Matrix4f view = (flip * T_wc.inverse().matrix()).cast<float>();
  const Eigen::Matrix4f proj = projection_matrix(m.K, kNear, kFar);
  const Eigen::Vector3f cam = T_wc.translation().cast<float>();
  glUniformMatrix4fv(m.loc_view, 1, GL_FALSE, view.data());
  glUniformMatrix4fv(m.loc_proj, 1, GL_FALSE, proj.data());
  glUniform3f(m.loc_cam, cam.x(), cam.y(), cam.z());
  glUniform1i(m.loc_tex, 0);
  glActiveTexture(GL_TEXTURE0);
  for (const DrawItem& it : items) {
    const MeshHandle& h = m.meshes.at(static_cast<std::size_t>(it.mesh));
    const Eigen::Matrix3f nm = it.model.topLeftCorner<3, 3>().inverse().transpose();
    glUniformMatrix4fv(m.loc_model, 1, GL_FALSE, it.model.data());
    glUniformMatrix3fv(m.loc_nm, 1, GL_FALSE, nm.data());
    glUniform1f(m.loc_id, static_cast<float>(it.object_id));
    glUniform1f(m.loc_tint, it.tint);
    glBindTexture(GL_TEXTURE_2D, m.textures.at(static_cast<std::size_t>(it.texture)));
    glBindVertexArray(h.vao);
    glDrawArrays(GL_TRIANGLES, 0, h.vertex_count);
  }
  glBindVertexArray(0);

  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, m.rgba.data());
  glReadBuffer(GL_COLOR_ATTACHMENT1);
  glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, m.geometry.data());
  glReadBuffer(GL_COLOR_ATTACHMENT2);
  glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, m.label.data());

  RenderedView out;
  out.bgr.create(H, W, CV_8UC3);
  out.depth.create(H, W, CV_32F);
  out.world.create(H, W, CV_32FC3);
  out.object_id.create(H, W, CV_8U);
  out.cos_incidence.create(H, W, CV_32F);
  for (int r = 0; r < H; ++r) {
    // OpenGL's row 0 is the bottom one.
    const std::size_t src_row = static_cast<std::size_t>(H - 1 - r) * static_cast<std::size_t>(W);
    auto* bgr = out.bgr.ptr<cv::Vec3b>(r);
    auto* depth = out.depth.ptr<float>(r);
    auto* world = out.world.ptr<cv::Vec3f>(r);
    auto* id = out.object_id.ptr<unsigned char>(r);
    auto* cosi = out.cos_incidence.ptr<float>(r);
    for (int c = 0; c < W; ++c) {
      const std::size_t k = (src_row + static_cast<std::size_t>(c)) * 4;
      bgr[c] = cv::Vec3b(m.rgba[k + 2], m.rgba[k + 1], m.rgba[k + 0]);
      world[c] = cv::Vec3f(m.geometry[k], m.geometry[k + 1], m.geometry[k + 2]);
      depth[c] = m.geometry[k + 3];
      id[c] = static_cast<unsigned char>(m.label[k] + 0.5f);
      cosi[c] = m.label[k + 1];
    }
  }
  return out;
}

}  // namespace hbos::render
