// libFuzzer target: the camera settings reader of hbos-slam (examples/slam/frontend/camera.hpp),
// JSON and YAML. load_camera takes a path, so the input is written to a private temporary file
// first. Documented outcomes: a camera whose fields lie in their legal ranges, or
// hbos::InvalidArgument naming the field.

#include <unistd.h>
#include <hbos/error.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

#include "frontend/camera.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const std::string base = "/tmp/hbos_fuzz_camera_" + std::to_string(getpid());
  const std::string path = base + ((data[0] & 1U) != 0 ? ".json" : ".yaml");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data) + 1, static_cast<std::streamsize>(size - 1));
  }
  try {
    const hbos::slam::CameraModel camera = hbos::slam::load_camera(path);
    // The documented legal ranges.
    if (!(camera.fx >= 1.0 && camera.fx <= 1e6 && camera.fy >= 1.0 && camera.fy <= 1e6))
      std::abort();
    if (!std::isfinite(camera.cx) || !std::isfinite(camera.cy)) std::abort();
    if (!(camera.depth_factor > 0.0 && camera.depth_factor <= 1e9)) std::abort();
    for (const double k : {camera.k1, camera.k2, camera.p1, camera.p2, camera.k3})
      if (!(std::abs(k) <= 1000.0)) std::abort();
  } catch (const hbos::InvalidArgument&) {
  }
  std::remove(path.c_str());
  return 0;
}
