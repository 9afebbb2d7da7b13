#pragma once
/// \file
/// The rendered sequences the benchmark runs on, generated into its cache by the `hbos-render`
/// executable (examples/render) and reused while they exist: the renderer writes into
/// `<out>.tmp` and renames, so a folder in the cache is always complete.

#include "dynbench/cells.hpp"

#include <cstdint>
#include <functional>
#include <string>

namespace hbos::dynbench {

/// The renderer this build knows (next to the benchmark's build), or empty when it was not
/// built (OSMesa missing).
[[nodiscard]] std::string built_renderer();

/// Renders `scenario` with `seed` into sequence_dir() unless it exists there (or
/// settings.rerender). Runs `settings.renderer --scenario S --seed N --out DIR --frames F
/// --quiet [--overwrite]`, its output in `<DIR>.log`. Returns the folder, or an empty string when
/// a signal stopped the run (examples::StopOnSignal) and the renderer with it. Throws
/// hbos::InvalidArgument when there is no renderer, and std::runtime_error naming the command
/// and the log's last lines when it fails.
std::string ensure_sequence(const BenchSettings& settings, const std::string& scenario,
                            std::uint64_t seed);

/// A hash (FNV-1a, 64 bit, hex) of the sequence's lists, ground truth and scenario.json and of
/// its first and last colour image: a re-rendered sequence that differs gets new cells.
[[nodiscard]] std::string sequence_fingerprint(const std::string& dir);

}  // namespace hbos::dynbench
