#pragma once
/// \file
/// Writes a rendered sequence as a TUM RGB-D folder that any TUM reader runs unchanged:
///   rgb/<stamp>.png, depth/<stamp>.png (16-bit, 5000/m), rgb.txt, depth.txt, groundtruth.txt,
///   associations.txt (ORB-SLAM2's format), objects/<stamp>.png (8-bit object ids),
///   masks/<variant>/<stamp>.png (0 = dynamic, 255 = static), scenario.json.
/// Everything is written into `<out>.tmp` and renamed to `<out>` at the end, so `<out>` is either
/// absent or complete.

#include <csignal>
#include <filesystem>
#include <functional>
#include <stdexcept>

#include "render/sequence.hpp"

namespace hbos::render {

/// The output folder cannot be used or written; `what()` names the path.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A signal asked the run to stop (see write_sequence's `stop`); nothing was written.
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What writing took.
struct WriteStats {
  int frames = 0;
  double seconds = 0.0;         ///< [s] wall time, rendering and writing
  double render_seconds = 0.0;  ///< [s] of which OpenGL rendering and read-back + sensor model
};

/// Called after each frame with (frames done, frames total).
using Progress = std::function<void(int, int)>;

/// Renders every frame of `r` and writes the folder `out` (which must not exist, unless
/// `overwrite`: then it is replaced once the new one is complete, and only if it is a previous
/// output of this function: a folder of other files, the current folder, `.` or `/` are refused
/// before anything is deleted). `stop`, polled between frames, ends the run when it becomes
/// non-zero (Ctrl-C); the unfinished `<out>.tmp` is removed on any failure.
/// \throws OutputError, Interrupted.
WriteStats write_sequence(SequenceRenderer& r, const std::filesystem::path& out, bool overwrite,
                          const Progress& progress = {},
                          const volatile std::sig_atomic_t* stop = nullptr);

/// TUM's stamp format: seconds with 6 decimals.
std::string format_stamp(double stamp);

}  // namespace hbos::render
