#pragma once
/// \file
/// Plots of an evaluation, drawn with OpenCV: the aligned estimate over the ground truth seen
/// from above, coloured by ATE, and the errors over time.

#include "eval/evaluate.hpp"
#include "eval/trajectory.hpp"

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace hbos::slam {

/// The plane a trajectory is projected on in the top view.
enum class PlotPlane {
  kXY,  ///< x right, y up: the top view for TUM and Bonn ground truth (z points up)
  kXZ,  ///< x right, z up
  kYZ,  ///< y right, z up
};

/// Parameters of the plots.
struct PlotParams {
  int width = 1000;                  ///< [px] of each image
  int height = 760;                  ///< [px] of each image
  PlotPlane plane = PlotPlane::kXY;  ///< projection of the top view
  /// Consecutive poses further apart in time than this many median periods are not joined by a
  /// line, so tracking losses show as gaps.
  double gap_factor = 5.0;  ///< [-]
};

/// The ground truth (grey line) and the aligned estimate (Evaluation::main_ate(), coloured by
/// its ATE per pose with a colour bar in metres), to scale (equal axes), with axis labels.
/// Returns an 8-bit BGR image. Throws hbos::InvalidArgument on invalid parameters.
[[nodiscard]] cv::Mat draw_top_view(const Trajectory& gt, const Evaluation& evaluation,
                                    const PlotParams& params = {});

/// ATE per associated pose over time since the first ground-truth stamp, with the RMSE, mean
/// and median drawn as labelled horizontal lines. 8-bit BGR.
[[nodiscard]] cv::Mat draw_ate_over_time(const Trajectory& gt, const Evaluation& evaluation,
                                         const PlotParams& params = {});

/// Translational (top) and rotational (bottom) RPE per pair over the time of its first pose,
/// with RMSE and mean lines, over time since the first ground-truth stamp. Throws
/// hbos::InvalidArgument without Evaluation::rpe. 8-bit BGR.
[[nodiscard]] cv::Mat draw_rpe_over_time(const Trajectory& gt, const Trajectory& est,
                                         const Evaluation& evaluation,
                                         const PlotParams& params = {});

/// Creates `dir` if needed and writes, each atomically, `top_view.png`, `ate_over_time.png` and
/// (when the RPE was computed) `rpe_over_time.png`. Returns the paths written. Throws
/// std::runtime_error on I/O failure.
std::vector<std::string> write_plots(const std::string& dir, const Trajectory& gt,
                                     const Trajectory& est, const Evaluation& evaluation,
                                     const PlotParams& params = {});

}  // namespace hbos::slam
