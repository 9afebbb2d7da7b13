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
///
/// What `path` names decides how it is written:
/// - `-`: standard output (not atomic, by nature).
/// - an existing file that is not a regular file (a character or block device such as
///   /dev/null, a FIFO, a socket): written in place, never renamed over (renaming would replace
///   the device node with a regular file). Not atomic, by nature; a FIFO blocks until it has a
///   reader, as `> fifo` does in a shell.
/// - a symbolic link: the link is kept and its final target is written by these same rules
///   (a dangling link creates its target).
/// - a directory: an error.
///
/// SIGINT, SIGTERM or SIGHUP while the temporary file exists removes it before the signal takes
/// its course (the previous disposition is restored and the signal re-raised): an interrupted
/// write leaves no `*.tmpNNN` file. If the previous disposition was a handler that returns (a
/// program that only sets a flag), the write is abandoned with a WriteError.
/// \throws WriteError on any failure.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// True when `output` names an existing file that is `input` itself (also through links or
/// another spelling of the path): writing it would replace the input. `-` (a standard stream)
/// and an empty path are never the same file as anything.
[[nodiscard]] bool is_same_file(const std::filesystem::path& output,
                                const std::filesystem::path& input);

/// The same, for content produced piece by piece (a result too large to hold as one string):
/// open, write() any number of times, commit(). Until commit() returns, readers of `path` see the
/// old file; destroying an AtomicFile that was not committed (an exception, an early return)
/// removes the temporary file and leaves `path` untouched. Special files (`-`, devices, FIFOs,
/// symbolic links) are handled as write_file_atomically describes. Not copyable; one thread.
class AtomicFile {
 public:
  /// Opens the temporary file (or the special file in place). \throws WriteError.
  explicit AtomicFile(const std::filesystem::path& path);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  /// Appends `content`. \throws WriteError (the temporary file is then removed).
  void write(std::string_view content);
  /// Flushes, closes and renames the temporary over the path. \throws WriteError.
  void commit();

 private:
  struct State;
  State* state_;
};

}  // namespace hbos::examples
