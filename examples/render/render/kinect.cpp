#include "render/kinect.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "render/random.hpp"

namespace hbos::render {

cv::Mat kinect_depth(const RenderedView& view, const Intrinsics& K, const KinectModel& m,
                     std::uint64_t seed, std::uint64_t frame) {
  const int W = view.depth.cols, H = view.depth.rows;
  cv::Mat out(H, W, CV_16U, cv::Scalar(0));
  Rng noise = stream(seed, Stream::kDepthNoise, frame);
  Rng holes = stream(seed, Stream::kDepthHoles, frame);
  const double fb = K.fx * m.baseline;  // [px m]: disparity = fb / z
  std::vector<unsigned char> shadow(static_cast<std::size_t>(W));
  for (int r = 0; r < H; ++r) {
    const float* z = view.depth.ptr<float>(r);
    const float* cosi = view.cos_incidence.ptr<float>(r);
    // Projector shadow: pixel u is not lit if some pixel q > u has d_q - q > d_u - u (d the
    // disparity), i.e. a nearer surface to its right hides it from the projector.
    double best = -std::numeric_limits<double>::infinity();
    for (int u = W - 1; u >= 0; --u) {
      const double d = z[u] > 0.f ? fb / static_cast<double>(z[u]) : 0.0;
      const double key = d - static_cast<double>(u);
      shadow[static_cast<std::size_t>(u)] = best > key + 0.5 ? 1 : 0;
      best = std::max(best, key);
    }
    auto* o = out.ptr<std::uint16_t>(r);
    double g4[4] = {0, 0, 0, 0}, h4[4] = {0, 0, 0, 0};
    for (int u = 0; u < W; ++u) {
      const double zu = static_cast<double>(z[u]);
      // Draw the noise first, always, so each pixel's draw does not depend on the others'.
      if ((u & 3) == 0) {
        noise.normal4(g4);
        holes.uniform4(h4);
      }
      const double g = g4[u & 3];
      const double h = h4[u & 3];
      if (zu < m.min_range || zu > m.max_range) continue;
      if (shadow[static_cast<std::size_t>(u)]) continue;
      const double c = static_cast<double>(cosi[u]);
      if (c < m.grazing_cos) continue;
      double sigma = m.sigma_a + m.sigma_b * (zu - m.sigma_z0) * (zu - m.sigma_z0);
      if (c < m.grazing_soft_cos) {
        const double s = (m.grazing_soft_cos - c) / (m.grazing_soft_cos - m.grazing_cos);
        if (h < 0.2 * s) continue;
        sigma *= 1.0 + 2.0 * s;
      }
      // Discontinuities: a 4-neighbour whose depth jumps by more than edge_jump * z.
      bool edge = false;
      const float zl = u > 0 ? z[u - 1] : z[u];
      const float zr = u + 1 < W ? z[u + 1] : z[u];
      const float zt = r > 0 ? view.depth.ptr<float>(r - 1)[u] : z[u];
      const float zb = r + 1 < H ? view.depth.ptr<float>(r + 1)[u] : z[u];
      for (float zn : {zl, zr, zt, zb}) {
        if (std::abs(static_cast<double>(zn) - zu) > m.edge_jump * zu) edge = true;
      }
      if (edge && h < m.edge_drop_probability) continue;
      const double zn = zu + sigma * g;
      const double units = std::round(zn * m.depth_scale);
      if (units <= 0.0 || units > 65535.0) continue;
      o[u] = static_cast<std::uint16_t>(units);
    }
  }
  return out;
}

cv::Mat kinect_rgb(const RenderedView& view, const KinectModel& m, std::uint64_t seed,
                   std::uint64_t frame) {
  cv::Mat blurred;
  cv::GaussianBlur(view.bgr, blurred, cv::Size(3, 3), m.rgb_blur_sigma, m.rgb_blur_sigma,
                   cv::BORDER_REPLICATE);
  Rng rng = stream(seed, Stream::kRgbNoise, frame);
  for (int r = 0; r < blurred.rows; ++r) {
    auto* p = blurred.ptr<unsigned char>(r);
    double g4[4] = {0, 0, 0, 0};
    for (int k = 0; k < blurred.cols * 3; ++k) {
      if ((k & 3) == 0) rng.normal4(g4);
      const double v = static_cast<double>(p[k]) + m.rgb_noise_sigma * g4[k & 3];
      p[k] = static_cast<unsigned char>(std::clamp(std::round(v), 0.0, 255.0));
    }
  }
  return blurred;
}

}  // namespace hbos::render
