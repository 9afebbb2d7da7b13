#pragma once
/// \file
/// Umbrella header: everything in hbos that needs nothing but Eigen.
/// The OpenCV adapter (hbos/opencv.hpp) is deliberately not included.

#include "hbos/binning.hpp"
#include "hbos/error.hpp"
#include "hbos/histogram.hpp"
#include "hbos/model.hpp"
#include "hbos/threshold.hpp"
#include "hbos/version.hpp"
#include "hbos/workspace.hpp"
