#pragma once
// Helpers shared by the front end's tests: the embedded data's paths and scratch folders.

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace hbos_test {

/// examples/slam/data (the data the front end embeds; defined by frontend/sources.cmake).
inline std::filesystem::path slam_data(const std::string& relative = "") {
  return std::filesystem::path(HBOS_SLAM_DATA_DIR) / relative;
}

/// A fresh folder under the system's temporary directory, removed with the object.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag) {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("hbos_frontend_" + tag + "_" + std::to_string(::getpid()) + "_" +
             std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }

  /// Writes `text` to `name` inside the folder and returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    const auto target = path_ / name;
    std::filesystem::create_directories(target.parent_path());
    std::ofstream(target) << text;
    return target.string();
  }

 private:
  std::filesystem::path path_;
};

}  // namespace hbos_test
