#pragma once
/// \file
/// The feature specs the core benchmarks compare, built in one place so that every benchmark
/// means the same thing by "static10" or "default".

#include "hbos/binning.hpp"
#include "hbos/model.hpp"

namespace hbos_bench {

/// Classic HBOS static bins: k equal-width bins, no shifts.
inline hbos::HbosParams static_bins(Eigen::Index k) {
  hbos::HbosParams params;
  params.feature.binning.method = hbos::BinningMethod::EqualWidth;
  params.feature.binning.rule = hbos::BinCountRule::Fixed;
  params.feature.binning.bins = k;
  params.feature.binning.shifts = 1;
  return params;
}

/// Goldstein & Dengel's dynamic bins: k equal-frequency bins.
inline hbos::HbosParams equal_frequency_bins(Eigen::Index k) {
  hbos::HbosParams params = static_bins(k);
  params.feature.binning.method = hbos::BinningMethod::EqualFrequency;
  return params;
}

/// Equal-width bins, their count chosen by Birgé–Rozenblac (PyOD's n_bins='auto' job).
inline hbos::HbosParams birge_rozenblac_bins() {
  hbos::HbosParams params = static_bins(1);
  params.feature.binning.rule = hbos::BinCountRule::BirgeRozenblac;
  return params;
}

/// Fixed-width bins anchored at 0 (the paper's residual binning), `width` in feature units.
inline hbos::HbosParams fixed_width_bins(double width) {
  hbos::HbosParams params;
  params.feature.binning.method = hbos::BinningMethod::FixedWidth;
  params.feature.binning.width = width;
  params.feature.binning.origin = 0.0;
  params.feature.binning.shifts = 1;
  return params;
}

template <class Scalar>
const char* scalar_name() {
  return sizeof(Scalar) == sizeof(float) ? "float" : "double";
}

}  // namespace hbos_bench
