#pragma once
/// \file
/// A map point's residual history as the screen's persistence evidence.
///
/// The default screen's history feature says how often a point was screened out before; a point
/// placed by one keyframe's depth error, or made on a slowly moving person, can be kept frame
/// after frame with a residual that never falls back to the frame's noise. The trimming screens
/// drop such points by their magnitude alone, with the noisier half of the good ones; the
/// default screen must not trim good points (the labelled cases' static-loss rule, where no
/// history exists), but it can hear a point's own record. Each point keeps the running mean q of
/// its squared whitened residual under the final pose of every frame that screened it, kept or
/// rejected (so a point can recover), and the screen receives
///   share = q / (q + ratio * median q)
/// where the median is over the frame's matched points with at least `min_frames` records: 0.5
/// exactly when q is `ratio` times the frame's typical value, the history feature's floor. The
/// value the screen sees is the larger of this share and the point's rejection share.

#include "frontend/map/point_noise.hpp"

#include <vector>

namespace hbos::slam {

/// Settings of the map tracker's residual history as screen evidence (docs/map_tracking.md).
struct NoiseHistoryConfig {
  bool enabled = false;
  double memory = 0.8;  ///< weight of the past per frame in a point's running mean, in [0, 1)
  double ratio = 2.0;   ///< q this many times the frame's median gives the share 0.5; >= 1
  int min_frames = 2;   ///< residuals recorded before a point's own record counts, >= 1
};

/// One share per point (see the file comment), in [0, 1]: 0 for a point with fewer than
/// `min_frames` records, and for every point when fewer than 10 have enough or their median is
/// 0. Throws on a setting out of range, naming it.
[[nodiscard]] std::vector<double> noise_shares(const std::vector<PointNoise>& noise,
                                               const NoiseHistoryConfig& config);

}  // namespace hbos::slam
