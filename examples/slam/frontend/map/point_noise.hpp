#pragma once
/// \file
/// A map point's own noise, learnt from its residuals under the refined poses.
///
/// The refinement whitens every residual by the keypoint's octave alone (ORB-SLAM2's model), as
/// if every map point sat where it belongs. A point made from one keyframe's depth carries that
/// depth's error, and a point on a slowly moving person drifts from where it was made: either
/// way its residual stays large frame after frame, with the same sign, and pulls every pose the
/// same way. The screen cannot tell such a point from the noisier half of good ones in one frame
/// (and must not drop it: the labelled cases' static-loss rule); its history can. Each point
/// keeps a running mean of its squared whitened residual under the final pose of each frame that
/// kept it,
///   q <- memory q + (1 - memory) e^2,
/// and the final refinement widens the sigma of a point whose q exceeds `tolerance` times the
/// median q of the frame's refined points by sqrt(q / (tolerance median)): a weight of
/// tolerance median / q, the inverse-variance weight of the noise the point has shown. The
/// median makes the reference the frame's own noise level, so a noisier frame or sensor does not
/// down-weight every point at once.

#include <cmath>
#include <cstdint>
#include <vector>

namespace hbos::slam {

/// Settings of the map tracker's per-point noise (docs/results.md, "Each map point's own noise").
struct PointNoiseConfig {
  bool enabled = false;
  double memory = 0.8;     ///< weight of the past per frame in the running mean, in [0, 1)
  double tolerance = 2.0;  ///< q up to this many times the frame's median keeps the full weight
  int min_frames = 2;      ///< residuals recorded before a point's own noise counts
};

class PointNoise {
 public:
  /// Records the squared whitened residual `e2` [px^2/sigma^2] of one frame's final pose.
  void record(double e2, double memory) {
    if (!std::isfinite(e2)) return;
    mean_square_ = frames_ == 0 ? e2 : memory * mean_square_ + (1.0 - memory) * e2;
    ++frames_;
  }
  /// [px^2/sigma^2] the running mean of the squared whitened residual; 0 before any record.
  [[nodiscard]] double mean_square() const { return mean_square_; }
  [[nodiscard]] int frames() const { return frames_; }

 private:
  double mean_square_ = 0.0;
  int frames_ = 0;
};

/// The frame's typical running mean: the median of `mean_square()` over the points with at least
/// `min_frames` records (and `use[i]` set, when `use` is given), or 0 when fewer than 10 points
/// qualify: too few to say what the frame's noise is.
[[nodiscard]] double median_mean_square(const std::vector<PointNoise>& noise, int min_frames,
                                        const std::vector<std::uint8_t>* use = nullptr);

/// Widens `sigma[i]` by sqrt(q_i / (tolerance median)) where point i's running mean q_i =
/// `noise[i].mean_square()` exceeds `tolerance` times the median q over the matches with
/// `use[i]` set (only points with at least `min_frames` records count, on either side). Fewer
/// than 10 such points among the used, or a median of 0: `sigma` is left as it is. Every
/// vector has one entry per match.
void widen_by_point_noise(const std::vector<PointNoise>& noise,
                          const std::vector<std::uint8_t>& use, const PointNoiseConfig& config,
                          std::vector<double>& sigma);

}  // namespace hbos::slam
