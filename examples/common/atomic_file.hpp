#pragma once
/// \file
/// Writing a result file so that readers see either the old file or the complete new one (shared
/// by every example command: hbos-score, the accuracy study, hbos-eval, hbos-slam).

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace hbos::examples {

/// A file could not be written; `what()` names the path and the system's reason.
class WriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Writes `content` to `path` atomically: into a new temporary file in the same directory
/// (created exclusively, so two writers never share one), then renamed over `path`. A failure at
/// any step removes the temporary file and leaves `path` untouched. Protects against a crash or
/// an error of this process, not against power loss (there is no fsync).
/// `path` == "-" writes to standard output instead (not atomic, by nature).
/// \throws WriteError on any failure.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace hbos::examples
