#pragma once
/// \file
/// The sensor: what a Kinect (v1, as in TUM RGB-D) makes of the rendered view.
///
/// Depth: axial noise with the standard deviation of Nguyen, Izadi & Lovell, "Modeling Kinect
/// Sensor Noise for Improved 3D Reconstruction and Tracking", 3DIMPVT 2012, eq. 6:
///   sigma_z(z) = 0.0012 + 0.0019 (z - 0.4)^2  [m],  for incidence angles below ~60 degrees,
/// growing as in their fig. 6 towards grazing angles; no return (0) outside the working range,
/// at grazing incidence, in the projector's shadow (the IR projector sits 7.5 cm beside the IR
/// camera, so the background next to a near object's edge is not lit: the stereo occlusion
/// test in disparity space) and, sporadically, on depth discontinuities. Stored as TUM does:
/// 16-bit PNG, 5000 units per metre.
/// Colour: a light blur (the Kinect's soft optics and Bayer interpolation) and Gaussian noise.

#include <cstdint>

#include <opencv2/core.hpp>

#include "render/camera.hpp"
#include "render/gl_renderer.hpp"

namespace hbos::render {

/// Parameters of the sensor model; every field has the documented default.
struct KinectModel {
  double min_range = 0.5;              ///< [m] nearer returns nothing
  double max_range = 5.0;              ///< [m] farther returns nothing
  double sigma_a = 0.0012;             ///< [m] Nguyen et al. 2012: constant term
  double sigma_b = 0.0019;             ///< [1/m] Nguyen et al. 2012: quadratic term
  double sigma_z0 = 0.4;               ///< [m] Nguyen et al. 2012: offset of the quadratic
  double grazing_cos = 0.17;           ///< |cos| below this (beyond ~80 deg): no return
  double grazing_soft_cos = 0.5;       ///< between the two (60..80 deg): noise x up to 3, holes
  double baseline = 0.075;             ///< [m] projector to IR camera (shadows left of near edges)
  double edge_jump = 0.04;             ///< relative depth jump that marks a discontinuity
  double edge_drop_probability = 0.5;  ///< chance a discontinuity pixel returns nothing
  double depth_scale = 5000.0;         ///< [units / m] TUM's PNG scale
  double rgb_blur_sigma = 0.6;         ///< [px]
  double rgb_noise_sigma = 2.0;        ///< [8-bit levels]
};

/// The Kinect's 16-bit depth image (0 = no return) of a rendered view; deterministic in
/// (seed, frame).
cv::Mat kinect_depth(const RenderedView& view, const Intrinsics& K, const KinectModel& model,
                     std::uint64_t seed, std::uint64_t frame);

/// The colour image as the sensor gives it; deterministic in (seed, frame).
cv::Mat kinect_rgb(const RenderedView& view, const KinectModel& model, std::uint64_t seed,
                   std::uint64_t frame);

}  // namespace hbos::render
