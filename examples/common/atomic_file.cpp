#include "common/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <random>
#include <system_error>

namespace hbos::examples {
namespace {

std::string reason() { return std::generic_category().message(errno); }

/// Writes all of `content` and closes `file`; false (with errno set) on any failure.
bool write_and_close(std::FILE* file, std::string_view content) {
  // fwrite's buffer is declared non-null even for a size of 0; an empty view may hold nullptr.
  const bool written =
      content.empty() || std::fwrite(content.data(), 1, content.size(), file) == content.size();
  const bool flushed = std::fflush(file) == 0;
  const int saved = errno;
  const bool closed = std::fclose(file) == 0;
  if (!(written && flushed)) errno = saved;
  return written && flushed && closed;
}

// ---- removing the temporary file on SIGINT / SIGTERM / SIGHUP ----------------------------------
// The handler may only use async-signal-safe calls (unlink, sigaction, raise), so the names of the
// temporaries live in fixed buffers that it reads: a few slots, one per AtomicFile open at once
// (a further one is written unprotected rather than refused).

constexpr std::array<int, 3> kSignals{SIGINT, SIGTERM, SIGHUP};
constexpr std::size_t kSlots = 4;
constexpr std::size_t kMaxPath = 4096;
std::array<std::array<char, kMaxPath>, kSlots> g_temporary{};  // NUL-terminated; "" = free
std::array<bool, kSlots> g_slot_used{};                        // by the main program only
std::size_t g_guards = 0;                                      // slots in use
volatile std::sig_atomic_t g_interrupted = 0;  // a signal arrived while a guard was active
std::array<struct sigaction, kSignals.size()> g_previous{};

extern "C" void remove_temporaries_on_signal(int sig) {
  const int saved = errno;
  for (auto& name : g_temporary) {
    if (name[0] != '\0') ::unlink(name.data());
    name[0] = '\0';
  }
  g_interrupted = 1;
  for (std::size_t k = 0; k < kSignals.size(); ++k) {
    if (kSignals[k] == sig) ::sigaction(sig, &g_previous[k], nullptr);
  }
  // The previous disposition now runs: the default ends the process, a handler sets its flag.
  ::raise(sig);
  errno = saved;
}

/// Blocks kSignals while alive, so that the handler never sees a half-written slot.
class SignalsBlocked {
 public:
  SignalsBlocked() {
    sigset_t block;
    sigemptyset(&block);
    for (const int sig : kSignals) sigaddset(&block, sig);
    ::pthread_sigmask(SIG_BLOCK, &block, &old_);
  }
  SignalsBlocked(const SignalsBlocked&) = delete;
  SignalsBlocked& operator=(const SignalsBlocked&) = delete;
  ~SignalsBlocked() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }

 private:
  sigset_t old_{};
};

/// While alive, an interrupting signal removes the temporary file `path` (see the header).
class TemporaryGuard {
 public:
  explicit TemporaryGuard(const std::string& path) {
    if (path.size() >= kMaxPath) return;  // unprotected, but still written
    const SignalsBlocked blocked;
    for (std::size_t k = 0; k < kSlots; ++k) {
      if (!g_slot_used[k]) {
        slot_ = k;
        break;
      }
    }
    if (slot_ == kSlots) return;
    g_slot_used[slot_] = true;
    std::memcpy(g_temporary[slot_].data(), path.c_str(), path.size() + 1);
    if (g_guards++ == 0) {
      g_interrupted = 0;
      struct sigaction action {};
      action.sa_handler = &remove_temporaries_on_signal;
      sigemptyset(&action.sa_mask);
      for (const int sig : kSignals) sigaddset(&action.sa_mask, sig);
      for (std::size_t k = 0; k < kSignals.size(); ++k) {
        ::sigaction(kSignals[k], &action, &g_previous[k]);
      }
    }
  }
  TemporaryGuard(const TemporaryGuard&) = delete;
  TemporaryGuard& operator=(const TemporaryGuard&) = delete;
  ~TemporaryGuard() {
    if (slot_ == kSlots) return;
    const SignalsBlocked blocked;
    g_temporary[slot_][0] = '\0';
    g_slot_used[slot_] = false;
    if (--g_guards == 0) {
      // Put the previous handlers back where ours is still installed (the handler already
      // restored the one of a signal it caught).
      for (std::size_t k = 0; k < kSignals.size(); ++k) {
        struct sigaction current {};
        ::sigaction(kSignals[k], nullptr, &current);
        if (current.sa_handler == &remove_temporaries_on_signal) {
          ::sigaction(kSignals[k], &g_previous[k], nullptr);
        }
      }
    }
  }
  /// Whether a signal removed the temporary files.
  [[nodiscard]] static bool interrupted() { return g_interrupted != 0; }

 private:
  std::size_t slot_ = kSlots;
};

// ---- what the path names -----------------------------------------------------------------------

/// Follows `path` through symbolic links to the file that a write should replace (at most 40
/// links, as the kernel allows); a dangling link yields the path it points to.
std::filesystem::path final_target(const std::filesystem::path& path) {
  std::filesystem::path current = path;
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code error;
    const auto status = std::filesystem::symlink_status(current, error);
    if (error || status.type() != std::filesystem::file_type::symlink) return current;
    const std::filesystem::path link = std::filesystem::read_symlink(current, error);
    if (error) throw WriteError("cannot read the symbolic link " + current.string());
    current = link.is_absolute() ? link : current.parent_path() / link;
  }
  throw WriteError(path.string() + ": too many levels of symbolic links");
}

std::FILE* create_exclusively(const std::string& path, std::string& temporary,
                              std::optional<TemporaryGuard>& guard) {
  // "wx" (C11, exclusive creation) fails instead of reusing an existing file, so a stale or
  // concurrent temporary is never overwritten; a random suffix makes a clash unlikely anyway.
  std::random_device entropy;
  for (int attempt = 0; attempt < 16; ++attempt) {
    temporary = path + ".tmp" + std::to_string(entropy() % 1000000u);
    guard.reset();
    guard.emplace(temporary);  // before the file exists: no moment without protection
    std::FILE* file = std::fopen(temporary.c_str(), "wx");
    if (file != nullptr) return file;
    if (errno != EEXIST) break;
  }
  const int error = errno;
  guard.reset();
  errno = error;
  return nullptr;
}

}  // namespace

struct AtomicFile::State {
  std::string path;       // as given, for messages
  std::string target;     // the file the rename replaces (links followed)
  std::string temporary;  // empty: written in place (stdout, a device, a FIFO)
  std::FILE* file = nullptr;
  bool owns_file = true;  // false for stdout
  bool committed = false;
  std::optional<TemporaryGuard> guard;

  [[nodiscard]] std::string written_name() const {
    if (!owns_file) return "standard output";
    return temporary.empty() ? path : temporary;
  }
  /// Closes and removes what is left of an unfinished write.
  void abandon() {
    if (file != nullptr && owns_file) std::fclose(file);
    file = nullptr;
    if (!temporary.empty()) std::remove(temporary.c_str());
    guard.reset();
  }
};

AtomicFile::AtomicFile(const std::filesystem::path& target) : state_(new State) {
  State& s = *state_;
  s.path = target.string();
  try {
    if (s.path == "-") {
      s.file = stdout;
      s.owns_file = false;
      return;
    }
    const std::filesystem::path file = final_target(target);
    std::error_code error;
    const auto status = std::filesystem::status(file, error);
    switch (status.type()) {
      case std::filesystem::file_type::not_found:
      case std::filesystem::file_type::regular:
        break;
      case std::filesystem::file_type::directory:
        throw WriteError(s.path + ": is a directory");
      case std::filesystem::file_type::none:  // status() failed, e.g. a parent not searchable
        throw WriteError("cannot write " + s.path + ": " + error.message());
      default:  // character/block device, FIFO, socket: never replace the node itself
        s.file = std::fopen(file.c_str(), "wb");
        if (s.file == nullptr) {
          throw WriteError("cannot open " + s.path + " for writing: " + reason());
        }
        return;
    }
    if (file.filename().empty()) throw WriteError(s.path + ": not a file name");
    s.target = file.string();
    s.file = create_exclusively(s.target, s.temporary, s.guard);
    if (s.file == nullptr) {
      s.temporary.clear();
      throw WriteError("cannot create a temporary file next to " + s.path + ": " + reason());
    }
  } catch (...) {
    delete state_;
    throw;
  }
}

AtomicFile::~AtomicFile() {
  if (!state_->committed) state_->abandon();
  delete state_;
}

void AtomicFile::write(std::string_view content) {
  State& s = *state_;
  if (s.file == nullptr || s.committed) throw WriteError(s.path + ": write after commit or error");
  if (!content.empty() &&
      std::fwrite(content.data(), 1, content.size(), s.file) != content.size()) {
    const std::string why = reason();
    const std::string name = s.written_name();
    s.abandon();
    throw WriteError("cannot write " + name + ": " + why);
  }
  if (TemporaryGuard::interrupted() && !s.temporary.empty()) {
    s.abandon();
    throw WriteError("interrupted while writing " + s.path + " (nothing written)");
  }
}

void AtomicFile::commit() {
  State& s = *state_;
  if (s.file == nullptr || s.committed) throw WriteError(s.path + ": commit after commit or error");
  const std::string name = s.written_name();
  if (!s.owns_file) {
    if (std::fflush(s.file) != 0) {
      const std::string why = reason();
      s.file = nullptr;
      throw WriteError("cannot write to standard output: " + why);
    }
    s.committed = true;
    return;
  }
  std::FILE* file = s.file;
  s.file = nullptr;
  if (!write_and_close(file, {})) {
    const std::string why = reason();
    s.abandon();
    throw WriteError("cannot write " + name + ": " + why);
  }
  if (s.temporary.empty()) {  // written in place
    s.committed = true;
    return;
  }
  if (TemporaryGuard::interrupted()) {
    s.abandon();
    throw WriteError("interrupted while writing " + s.path + " (nothing written)");
  }
  std::error_code error;
  std::filesystem::rename(s.temporary, s.target, error);
  if (error || TemporaryGuard::interrupted()) {
    const std::string message = "cannot rename " + s.temporary + " to " + s.path + ": " +
                                (error ? error.message() : std::string("interrupted"));
    s.abandon();
    throw WriteError(message);
  }
  s.committed = true;
  s.guard.reset();
}

void write_file_atomically(const std::filesystem::path& target, std::string_view content) {
  AtomicFile file(target);
  file.write(content);
  file.commit();
}

bool is_same_file(const std::filesystem::path& output, const std::filesystem::path& input) {
  if (output.empty() || input.empty() || output == "-" || input == "-") return false;
  std::error_code ec;
  if (!std::filesystem::exists(output, ec) || !std::filesystem::exists(input, ec)) return false;
  const bool same = std::filesystem::equivalent(output, input, ec);
  return !ec && same;
}

}  // namespace hbos::examples
