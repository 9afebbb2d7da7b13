#include "dynbench/sequences.hpp"

#include "common/stop_on_signal.hpp"
#include "frontend/dataset.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

namespace hbos::dynbench {

namespace fs = std::filesystem;

namespace {

std::string tail_of(const std::string& path, std::size_t lines) {
  std::ifstream in(path);
  std::deque<std::string> last;
  std::string line;
  while (std::getline(in, line)) {
    last.push_back(line);
    if (last.size() > lines) last.pop_front();
  }
  std::string text;
  for (const std::string& l : last) text += "\n  " + l;
  return text;
}

// Runs argv[0] with argv, stdout and stderr into `log`; returns the exit status (or -1 when it
// could not be started, -2 when killed by a signal).
int run_logged(const std::vector<std::string>& argv, const std::string& log) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, STDOUT_FILENO);
      ::dup2(fd, STDERR_FILENO);
      ::close(fd);
    }
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return -2;
}

std::uint64_t fnv1a(std::uint64_t h, const std::string& bytes) {
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ULL;
  }
  return h;
}

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

std::string built_renderer() {
#ifdef HBOS_DYNBENCH_RENDERER
  return HBOS_DYNBENCH_RENDERER;
#else
  return {};
#endif
}

std::string ensure_sequence(const BenchSettings& settings, const std::string& scenario,
                            std::uint64_t seed) {
  const std::string dir = sequence_dir(settings, scenario, seed);
  if (fs::is_directory(dir) && !settings.rerender) return dir;
  if (settings.renderer.empty()) {
    throw InvalidArgument(
        "no renderer: hbos-render was not built (it needs OSMesa: apt-get install "
        "libosmesa6-dev) and --renderer was not given");
  }
  if (!fs::is_regular_file(settings.renderer)) {
    throw InvalidArgument(fmt::format("renderer '{}' does not exist", settings.renderer));
  }
  std::error_code error;
  fs::create_directories(settings.cache_dir, error);
  if (error) {
    throw InvalidArgument(
        fmt::format("cannot create cache '{}': {}", settings.cache_dir, error.message()));
  }
  std::vector<std::string> argv = {settings.renderer,
                                   "--scenario",
                                   scenario,
                                   "--seed",
                                   std::to_string(seed),
                                   "--out",
                                   dir,
                                   "--frames",
                                   std::to_string(settings.frames),
                                   "--quiet"};
  if (settings.people > 0) {
    argv.emplace_back("--people");
    argv.emplace_back(std::to_string(settings.people));
  }
  if (fs::exists(dir)) argv.emplace_back("--overwrite");
  const std::string log = dir + ".log";
  const int status = run_logged(argv, log);
  if (status != 0 && examples::StopOnSignal::stopped()) {
    // Ctrl-C reached the renderer too (the terminal signals the whole process group): not a
    // failure. The renderer removes its temporary folder itself; a second Ctrl-C may not let it.
    std::error_code ignored;
    fs::remove_all(dir + ".tmp", ignored);
    return {};
  }
  if (status != 0 || !fs::is_directory(dir)) {
    std::string command;
    for (const std::string& a : argv) command += (command.empty() ? "" : " ") + a;
    throw std::runtime_error(
        fmt::format("rendering failed (exit status {}): {}{}", status, command, tail_of(log, 8)));
  }
  return dir;
}

std::string sequence_fingerprint(const std::string& dir) {
  std::uint64_t h = 14695981039346656037ULL;
  for (const char* name : {"rgb.txt", "depth.txt", "groundtruth.txt", "scenario.json"}) {
    h = fnv1a(h, name);
    h = fnv1a(h, file_bytes(fs::path(dir) / name));
  }
  const std::vector<slam::ListedImage> rgb =
      slam::read_image_list((fs::path(dir) / "rgb.txt").string());
  h = fnv1a(h, file_bytes(fs::path(dir) / rgb.front().path));
  h = fnv1a(h, file_bytes(fs::path(dir) / rgb.back().path));
  return fmt::format("{:016x}", h);
}

}  // namespace hbos::dynbench
