#pragma once
/// \file
/// Umbrella header: everything in hbos that needs nothing but Eigen — the core (binning,
/// histograms, the model, thresholds, the per-frame workspace), the PyOD-compatible mode and the
/// reprojection-residual screen. The OpenCV adapter (hbos/opencv.hpp) is deliberately not
/// included: include it yourself where OpenCV is available.

#include "hbos/binning.hpp"
#include "hbos/error.hpp"
#include "hbos/histogram.hpp"
#include "hbos/model.hpp"
#include "hbos/pyod.hpp"
#include "hbos/reprojection.hpp"
#include "hbos/threshold.hpp"
#include "hbos/version.hpp"
#include "hbos/workspace.hpp"
