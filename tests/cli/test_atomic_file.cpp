// Tests of examples/common/atomic_file.hpp.

#include "common/atomic_file.hpp"

#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// A fresh, empty directory for one test.
fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(HBOS_CLI_WORK_DIR) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST_CASE("atomic writes create and replace files and leave no temporary behind", "[atomic_file]") {
  const fs::path dir = fresh_dir("atomic_replace");
  const fs::path path = dir / "out.csv";
  hbos::examples::write_file_atomically(path.string(), "first\n");
  CHECK(slurp(path) == "first\n");
  const std::string big(1 << 20, 'x');
  hbos::examples::write_file_atomically(path.string(), big);
  CHECK(slurp(path) == big);
  hbos::examples::write_file_atomically(path.string(), "");
  CHECK(slurp(path).empty());
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
}

TEST_CASE("a failed atomic write throws and leaves the target untouched", "[atomic_file][errors]") {
  const fs::path dir = fresh_dir("atomic_failure");
  REQUIRE_THROWS_AS(
      hbos::examples::write_file_atomically((dir / "missing" / "out.csv").string(), "x"),
      hbos::examples::WriteError);
  REQUIRE_THROWS_WITH(
      hbos::examples::write_file_atomically((dir / "missing" / "out.csv").string(), "x"),
      Catch::Contains("cannot create a temporary file next to") &&
          Catch::Contains("No such file or directory"));

  // The target is a directory: refused up front, the directory survives, no temporary.
  const fs::path target = dir / "taken";
  fs::create_directories(target / "inside");
  REQUIRE_THROWS_WITH(hbos::examples::write_file_atomically(target.string(), "x"),
                      Catch::Contains("taken: is a directory"));
  CHECK(fs::is_directory(target / "inside"));
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
}

TEST_CASE("a character device is written in place, never replaced by a regular file",
          "[atomic_file][special]") {
  const fs::path dir = fresh_dir("atomic_device");
  const fs::path device = dir / "null";
  // The null device's numbers (1, 3), made in our own folder: never the system's /dev/null.
  if (::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0) {
    WARN("mknod needs root; the device case is not checked here");
    return;
  }
  hbos::examples::write_file_atomically(device, "discarded\n");
  CHECK(fs::is_character_file(device));
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
}

TEST_CASE("a FIFO is written in place, and its reader gets the content", "[atomic_file][special]") {
  const fs::path dir = fresh_dir("atomic_fifo");
  const fs::path fifo = dir / "pipe";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  std::string received;
  std::thread reader([&] { received = slurp(fifo); });
  hbos::examples::write_file_atomically(fifo, "through the pipe\n");
  reader.join();
  CHECK(received == "through the pipe\n");
  CHECK(fs::is_fifo(fifo));
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
}

TEST_CASE("a symlinked output keeps the link and its target is replaced atomically",
          "[atomic_file][special]") {
  const fs::path dir = fresh_dir("atomic_symlink");
  fs::create_directories(dir / "real");
  std::ofstream(dir / "real" / "out.csv") << "old\n";
  fs::create_symlink("real/out.csv", dir / "link.csv");  // relative, as `ln -s` makes them
  hbos::examples::write_file_atomically(dir / "link.csv", "new\n");
  CHECK(fs::is_symlink(dir / "link.csv"));
  CHECK(slurp(dir / "real" / "out.csv") == "new\n");
  CHECK(std::distance(fs::directory_iterator(dir / "real"), fs::directory_iterator()) == 1);

  // A dangling link creates its target.
  fs::create_symlink("real/later.csv", dir / "dangling.csv");
  hbos::examples::write_file_atomically(dir / "dangling.csv", "created\n");
  CHECK(fs::is_symlink(dir / "dangling.csv"));
  CHECK(slurp(dir / "real" / "later.csv") == "created\n");
}

TEST_CASE("SIGINT during an atomic write leaves no temporary file behind",
          "[atomic_file][signal]") {
  const fs::path dir = fresh_dir("atomic_sigint");
  const fs::path target = dir / "out.csv";
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    // The test framework's own handlers stay out of the child: SIGINT must do what it does in
    // a plain program (end it) once the writer has removed its temporary.
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    // Writes 64 MiB again and again until the parent interrupts it mid-write.
    const std::string big(std::size_t{64} << 20, 'x');
    for (int k = 0; k < 1000; ++k) hbos::examples::write_file_atomically(target, big);
    ::_exit(0);
  }
  // Wait until a temporary exists (the child is inside a write), then interrupt.
  bool seen = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!seen && std::chrono::steady_clock::now() < deadline) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (entry.path().filename().string().find(".tmp") != std::string::npos) seen = true;
    }
    if (!seen) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  ::kill(child, SIGINT);
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  CHECK(seen);
  CHECK(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGINT);
  for (const auto& entry : fs::directory_iterator(dir)) {
    INFO(entry.path());
    CHECK(entry.path().filename() == "out.csv");
  }
}
