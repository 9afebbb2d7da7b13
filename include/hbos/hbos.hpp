#pragma once
/// \file
/// Umbrella header of the core: binning, histograms, the model, thresholds, the per-frame
/// workspace. Eigen only. The PyOD-compatible mode (hbos/pyod.hpp) and the reprojection screen
/// (hbos/screening.hpp) have umbrellas of their own; the OpenCV adapter
/// (hbos/screening/opencv.hpp) is included by nothing.

#include "hbos/binning.hpp"
#include "hbos/error.hpp"
#include "hbos/histogram.hpp"
#include "hbos/model.hpp"
#include "hbos/threshold.hpp"
#include "hbos/version.hpp"
#include "hbos/workspace.hpp"
