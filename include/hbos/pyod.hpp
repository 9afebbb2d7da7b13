#pragma once
/// \file
/// The PyOD-compatible mode in one include: `hbos::PyodHbos` (hbos/pyod/model.hpp), scoring
/// bit-identically to PyOD 3.6.5's HBOS, and its numpy replicas (hbos/pyod/detail/). Eigen only;
/// not part of the core umbrella hbos/hbos.hpp.

#include "hbos/pyod/model.hpp"
