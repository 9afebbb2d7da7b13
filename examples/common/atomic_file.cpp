#include "common/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <random>
#include <system_error>

namespace hbos::examples {
namespace {

std::string reason() { return std::generic_category().message(errno); }

/// Writes all of `content` and closes `file`; false (with errno set) on any failure.
bool write_and_close(std::FILE* file, std::string_view content) {
  const bool written = std::fwrite(content.data(), 1, content.size(), file) == content.size();
  const bool flushed = std::fflush(file) == 0;
  const int saved = errno;
  const bool closed = std::fclose(file) == 0;
  if (!(written && flushed)) errno = saved;
  return written && flushed && closed;
}

}  // namespace

void write_file_atomically(const std::filesystem::path& target, std::string_view content) {
  const std::string path = target.string();
  if (path == "-") {
    const bool written = std::fwrite(content.data(), 1, content.size(), stdout) == content.size();
    if (!written || std::fflush(stdout) != 0) {
      throw WriteError("cannot write to standard output: " + reason());
    }
    return;
  }
  if (target.filename().empty()) throw WriteError(path + ": not a file name");

  // "wx" (C11, exclusive creation) fails instead of reusing an existing file, so a stale or
  // concurrent temporary is never overwritten; a random suffix makes a clash unlikely anyway.
  std::random_device entropy;
  std::FILE* file = nullptr;
  std::string temporary;
  for (int attempt = 0; attempt < 16 && file == nullptr; ++attempt) {
    temporary = path + ".tmp" + std::to_string(entropy() % 1000000u);
    file = std::fopen(temporary.c_str(), "wx");
    if (file == nullptr && errno != EEXIST) break;
  }
  if (file == nullptr) {
    throw WriteError("cannot create a temporary file next to " + path + ": " + reason());
  }
  if (!write_and_close(file, content)) {
    const std::string why = reason();
    std::remove(temporary.c_str());
    throw WriteError("cannot write " + temporary + ": " + why);
  }
  std::error_code error;
  std::filesystem::rename(temporary, target, error);
  if (error) {
    std::remove(temporary.c_str());
    throw WriteError("cannot rename " + temporary + " to " + path + ": " + error.message());
  }
}

}  // namespace hbos::examples
