#pragma once
/// \file
/// Stage 1a from files: dynamic-object masks a segmenter wrote beforehand (Mask R-CNN, YOLO, a
/// renderer's ground truth), and per-pixel ground-truth object ids, matched to the frames of a
/// sequence. Every frame's file is resolved and its size checked when the object is built, so a
/// missing or wrongly sized file stops the run before its first frame, naming the file.

#include "frontend/config.hpp"
#include "frontend/dataset.hpp"

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace hbos::slam {

/// `dynaslam` (0 = dynamic, non-zero = static: DynaSLAM's files) or `nonzero-dynamic`.
[[nodiscard]] const char* to_string(MaskConvention convention);
/// Inverse of to_string; throws hbos::InvalidArgument naming the value and the choices.
[[nodiscard]] MaskConvention parse_mask_convention(const std::string& name);

/// One image per frame of a sequence, found in a folder. Frame i's file is the one with the stem
/// of its colour image (`rgb/1305031102.175304.png` -> `1305031102.175304.*`); failing that, the
/// file whose stem is a timestamp nearest to the frame's stamp and less than `max_difference`
/// away. Image files are `.png`, `.jpg`, `.jpeg`, `.bmp`, `.tif`, `.tiff`, `.pgm`, `.ppm`.
class FrameImageFiles {
 public:
  /// Resolves every frame's file and checks that its size is the colour image's. Throws
  /// hbos::InvalidArgument when `dir` is not a folder, a frame has no file (naming the frame, its
  /// colour image and list line, and what was looked for), or a file's size differs (naming the
  /// file, the expected and the actual size). `what` names the files in messages ("mask").
  FrameImageFiles(const RgbdSequence& sequence, const std::string& dir, double max_difference,
                  const std::string& what);

  [[nodiscard]] int size() const { return static_cast<int>(paths_.size()); }
  [[nodiscard]] const std::string& path(int index) const;
  /// Frame `index`'s image as stored (cv::IMREAD_UNCHANGED), several channels reduced to one
  /// that is non-zero where any channel is. Throws hbos::InvalidArgument when it cannot be read
  /// or its size changed since the check.
  [[nodiscard]] cv::Mat read(int index) const;

 private:
  std::vector<std::string> paths_;
  cv::Size size_;
  std::string what_;
};

/// Masks from files: CV_8U, 255 = dynamic (no features are extracted there).
class MaskFiles {
 public:
  /// As FrameImageFiles, with the files' convention.
  MaskFiles(const RgbdSequence& sequence, const std::string& dir, MaskConvention convention,
            double max_difference);
  [[nodiscard]] cv::Mat mask(int index) const;
  [[nodiscard]] const std::string& path(int index) const { return files_.path(index); }

 private:
  FrameImageFiles files_;
  MaskConvention convention_;
};

/// Ground-truth labels from an `objects/` folder (a rendered sequence's): per pixel the id of
/// the dynamic object seen there, 0 = static background. label() is CV_8U, 255 = on a dynamic
/// object, the label the front end's statistics count matches against.
class ObjectLabels {
 public:
  ObjectLabels(const RgbdSequence& sequence, const std::string& dir, double max_difference);
  [[nodiscard]] cv::Mat label(int index) const;

 private:
  FrameImageFiles files_;
};

/// `<sequence root>/objects` when that folder exists, else empty: where FrameSource looks for
/// ground-truth labels when ScenarioConfig::objects_dir is empty.
[[nodiscard]] std::string default_objects_dir(const RgbdSequence& sequence);

}  // namespace hbos::slam
