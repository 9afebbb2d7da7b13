#pragma once
/// \file
/// The photographic textures: real TUM / slambook2 frames shipped in examples/render/data/textures
/// (see its SOURCE.md), and the crops of them that dress the room and the people.

#include <filesystem>
#include <map>
#include <string>

#include <opencv2/core.hpp>

namespace hbos::render {

/// The folder of the renderer's data (textures/, trajectories/): the source tree's
/// examples/render/data, fixed at build time; a caller may pass another.
std::filesystem::path default_data_dir();

/// Named 8-bit BGR images, cut from the shipped frames.
class TextureLibrary {
 public:
  /// Loads the frames from `data_dir`/textures and cuts the named crops.
  /// \throws InputError naming the file that is missing or unreadable.
  explicit TextureLibrary(const std::filesystem::path& data_dir);

  /// The image called `name` (see textures.cpp for the list).
  /// \throws std::out_of_range for an unknown name.
  const cv::Mat& get(const std::string& name) const { return images_.at(name); }

  /// A new image: `a` and `b` side by side at `a`'s height (a two-region atlas: u < split is
  /// `a`). `split` receives the u coordinate of the seam.
  static cv::Mat side_by_side(const cv::Mat& a, const cv::Mat& b, float& split);

 private:
  std::map<std::string, cv::Mat> images_;
};

}  // namespace hbos::render
