#pragma once
/// \file
/// Writing result files atomically: readers see the old file or the complete new one, never a
/// half-written file, even when the process dies mid-write.

#include <filesystem>
#include <string_view>

namespace hbos::slam {

/// Writes `bytes` to a temporary file in the directory of `path`, then renames it over `path`
/// (rename is atomic within one file system, hence the same directory). Throws
/// std::runtime_error naming the path and the system error on failure; the temporary file is
/// removed in that case.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace hbos::slam
