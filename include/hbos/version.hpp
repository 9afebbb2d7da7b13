#pragma once
/// \file
/// The library version: the single source of truth (CMake parses it from here).

#define HBOS_VERSION_MAJOR 0
#define HBOS_VERSION_MINOR 5
#define HBOS_VERSION_PATCH 1

namespace hbos {
inline constexpr int kVersionMajor = HBOS_VERSION_MAJOR;
inline constexpr int kVersionMinor = HBOS_VERSION_MINOR;
inline constexpr int kVersionPatch = HBOS_VERSION_PATCH;
}  // namespace hbos
