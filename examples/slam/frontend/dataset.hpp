#pragma once
/// \file
/// A TUM RGB-D sequence on disk: `rgb.txt` and `depth.txt` (`timestamp filename` per line,
/// `#` comments), each colour image paired with the depth image nearest in time, and the
/// optional `groundtruth.txt`. Every error names the file and line.

#include "eval/trajectory.hpp"

#include <opencv2/core.hpp>

#include <optional>
#include <string>
#include <vector>

namespace hbos::slam {

/// One line of an rgb.txt / depth.txt list.
struct ListedImage {
  double stamp = 0.0;  ///< [s]
  std::string path;    ///< as written in the list, relative to the sequence folder
  int line = 0;        ///< line number in the list file, for messages
};

/// Reads a TUM image list. Throws hbos::InvalidArgument naming `file:line` on a line that is not
/// `timestamp filename`, a stamp that is not a finite number or does not increase, and when the
/// file cannot be opened or lists no image.
[[nodiscard]] std::vector<ListedImage> read_image_list(const std::string& path);

/// One RGB-D frame of a sequence: a colour image and the depth image nearest in time.
struct FrameRecord {
  ListedImage rgb;
  ListedImage depth;
};

struct RgbdSequence {
  std::string root;                       ///< the sequence folder
  std::vector<FrameRecord> frames;        ///< in time order
  Eigen::Index unpaired_rgb = 0;          ///< colour images without a depth image within the limit
  std::optional<Trajectory> groundtruth;  ///< groundtruth.txt, when the folder has one

  [[nodiscard]] Eigen::Index size() const { return static_cast<Eigen::Index>(frames.size()); }
  [[nodiscard]] std::vector<double> rgb_stamps() const;
};

/// Loads the lists (and ground truth, if present) of the sequence in `folder`. Each colour image
/// is paired with the depth image nearest in time when they are less than `max_difference`
/// seconds apart; colour images without such a depth image are skipped (counted in unpaired_rgb).
/// Throws hbos::InvalidArgument when a list is missing or malformed or no pair is found.
[[nodiscard]] RgbdSequence load_tum_sequence(const std::string& folder,
                                             double max_difference = 0.02);

/// The images of one frame: colour 8-bit BGR, depth in metres (CV_32F, 0 = no measurement).
struct RgbdImages {
  cv::Mat bgr;
  cv::Mat depth_m;
};

/// Checks, before a run starts, that every image of the first `frames` frames (0 = all) exists,
/// is a regular file and can be opened; throws hbos::InvalidArgument naming the first that is
/// not (and its list line). Decoding is left to read_frame_images.
void check_sequence_files(const RgbdSequence& sequence, Eigen::Index frames);

/// Reads frame `index`. Throws hbos::InvalidArgument naming the image (and the list line) when it
/// does not exist, is a directory, cannot be read, is a truncated JPEG (no end marker FF D9) or
/// PNG (no IEND chunk), cannot be decoded, is not 8-bit colour / 16-bit depth, or the two sizes
/// differ.
[[nodiscard]] RgbdImages read_frame_images(const RgbdSequence& sequence, Eigen::Index index,
                                           double depth_factor);

}  // namespace hbos::slam
