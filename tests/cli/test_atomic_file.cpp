// Tests of examples/common/atomic_file.hpp.

#include "common/atomic_file.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

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

  // The target is a directory: the rename fails, the directory survives, the temporary is gone.
  const fs::path target = dir / "taken";
  fs::create_directories(target / "inside");
  REQUIRE_THROWS_WITH(hbos::examples::write_file_atomically(target.string(), "x"),
                      Catch::Contains("cannot rename"));
  CHECK(fs::is_directory(target / "inside"));
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
}
