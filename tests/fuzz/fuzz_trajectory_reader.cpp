// libFuzzer target: the TUM trajectory reader of hbos-eval (examples/slam/eval/trajectory_io.hpp)
// under both stamp policies. Documented outcomes: a trajectory or hbos::InvalidArgument.

#include <hbos/error.hpp>

#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "eval/trajectory_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  hbos::slam::ReadOptions options;
  options.stamps = (data[0] & 1U) != 0 ? hbos::slam::StampPolicy::kLikeTumScripts
                                       : hbos::slam::StampPolicy::kStrict;
  std::istringstream stream(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  hbos::slam::ReadReport report;
  try {
    const hbos::slam::Trajectory t =
        hbos::slam::parse_tum_trajectory(stream, "fuzz.txt", options, &report);
    if (report.poses < 1) std::abort();  // documented: a file without a pose throws
    (void)t;
  } catch (const hbos::InvalidArgument&) {
  }
  return 0;
}
