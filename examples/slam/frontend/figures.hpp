#pragma once
/// \file
/// The pictures of a run, for people who would rather look than read: which matches the screen
/// kept and rejected on one frame, and the residual histogram with the screen's cut.

#include "frontend/sequence_run.hpp"

#include <opencv2/core.hpp>

#include <string>

namespace hbos::slam {

/// The frame with every screened match as a short flow line ending in a dot, green = kept,
/// red = rejected (a ring marks matches on the person label), the person label outlined in
/// yellow, the extraction mask in cyan and detector boxes in blue, and a legend. 8-bit BGR.
[[nodiscard]] cv::Mat draw_match_figure(const FigureFrame& figure, const std::string& title);

/// Histogram of the screen's residual magnitude on the figure frame, stacked by label and
/// decision (static kept / rejected, person kept / rejected), with the cut as a vertical line:
/// the strategy's own threshold for gates, the smallest rejected magnitude for HBOS (whose cut
/// is on a histogram score). Magnitudes beyond the axis are counted in the last bin. 8-bit BGR.
[[nodiscard]] cv::Mat draw_residual_histogram(const FigureFrame& figure, const std::string& title);

/// Writes a PNG atomically (encode, then write_file_atomically). Throws std::runtime_error.
void write_png(const std::string& path, const cv::Mat& image);

}  // namespace hbos::slam
