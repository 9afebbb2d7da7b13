#include "frontend/person_detector.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace hbos::slam {
namespace {

// OpenCV's Darknet reader fills whatever a short weights file lacks without a word, and the
// network then detects nothing, or noise. The file must hold every weight the cfg asks for:
// Darknet's header (three int32 version numbers, then the images seen: int64 from version 0.2,
// int32 before) and, per convolution, its weights and biases and, with batch normalisation, the
// scales, means and variances: in OpenCV's network, the blobs of its Convolution and BatchNorm
// layers (the Region layers' anchors come from the cfg).
void check_weights_size(cv::dnn::Net& net, const std::string& weights) {
  std::ifstream in(weights, std::ios::binary);
  std::int32_t version[3] = {0, 0, 0};
  in.read(reinterpret_cast<char*>(version), sizeof version);
  const std::uintmax_t bytes = std::filesystem::file_size(weights);
  // Darknet's own test, in 64 bits: a damaged header's numbers must not overflow it.
  const std::int64_t major = version[0], minor = version[1];
  const bool long_seen = major * 10 + minor >= 2 && major < 1000 && minor < 1000;
  const std::uintmax_t header = 12 + (long_seen ? 8 : 4);
  std::uintmax_t needed = 0;
  for (const std::string& name : net.getLayerNames()) {
    const cv::Ptr<cv::dnn::Layer> layer = net.getLayer(name);
    if (layer->type != "Convolution" && layer->type != "BatchNorm") continue;
    for (const cv::Mat& blob : layer->blobs) needed += blob.total();
  }
  const std::uintmax_t needed_bytes = header + 4 * needed;
  if (!in || bytes < needed_bytes) {
    throw InvalidArgument(fmt::format(
        "detector weights '{}' are truncated: {} bytes, the network of its cfg needs {} ({} "
        "weights after a {}-byte header)",
        weights, bytes, needed_bytes, needed, header));
  }
}

}  // namespace

PersonDetector::PersonDetector(const MaskConfig& config)
    : confidence_(config.detector_confidence),
      nms_(config.detector_nms),
      input_px_(config.detector_input_px) {
  namespace fs = std::filesystem;
  if (!(confidence_ > 0.f && confidence_ < 1.f) || !(nms_ > 0.f && nms_ <= 1.f) || input_px_ < 32 ||
      input_px_ % 32 != 0) {
    throw InvalidArgument(fmt::format(
        "detector settings: confidence {} must lie in (0, 1), nms {} in (0, 1], input {} px a "
        "multiple of 32",
        confidence_, nms_, input_px_));
  }
  const fs::path dir(config.detector_dir);
  const std::string cfg = (dir / "yolo-fastest-1.1_body.cfg").string();
  const std::string weights = (dir / "yolo-fastest-1.1_body.weights").string();
  for (const std::string& file : {cfg, weights}) {
    if (!fs::is_regular_file(file)) {
      throw InvalidArgument(fmt::format("detector model file '{}' not found", file));
    }
  }
  try {
    net_ = cv::dnn::readNetFromDarknet(cfg, weights);
  } catch (const cv::Exception& e) {
    throw InvalidArgument(fmt::format("cannot load detector '{}': {}", cfg, e.what()));
  }
  if (net_.empty()) throw InvalidArgument(fmt::format("cannot load detector '{}'", cfg));
  check_weights_size(net_, weights);
  output_names_ = net_.getUnconnectedOutLayersNames();
}

std::vector<PersonBox> PersonDetector::detect(const cv::Mat& bgr) {
  // Darknet was trained on RGB scaled to [0, 1], letterbox-free at the network's square size.
  const cv::Mat blob = cv::dnn::blobFromImage(bgr, 1.0 / 255.0, cv::Size(input_px_, input_px_),
                                              cv::Scalar(), /*swapRB=*/true, /*crop=*/false);
  net_.setInput(blob);
  std::vector<cv::Mat> outputs;
  net_.forward(outputs, output_names_);

  // Each row: centre x, centre y, width, height (normalised), objectness, class score.
  std::vector<cv::Rect> boxes;
  std::vector<float> scores;
  const cv::Rect image(0, 0, bgr.cols, bgr.rows);
  for (const cv::Mat& out : outputs) {
    for (int r = 0; r < out.rows; ++r) {
      const float* row = out.ptr<float>(r);
      const float score = row[5];
      if (!(score >= confidence_)) continue;
      const float w = row[2] * static_cast<float>(bgr.cols);
      const float h = row[3] * static_cast<float>(bgr.rows);
      const float x = row[0] * static_cast<float>(bgr.cols) - 0.5f * w;
      const float y = row[1] * static_cast<float>(bgr.rows) - 0.5f * h;
      const cv::Rect box =
          cv::Rect(static_cast<int>(std::lround(x)), static_cast<int>(std::lround(y)),
                   static_cast<int>(std::lround(w)), static_cast<int>(std::lround(h))) &
          image;
      if (box.area() == 0) continue;
      boxes.push_back(box);
      scores.push_back(score);
    }
  }
  std::vector<int> keep;
  cv::dnn::NMSBoxes(boxes, scores, confidence_, nms_, keep);
  std::vector<PersonBox> people;
  for (const int k : keep) {
    people.push_back({boxes[static_cast<std::size_t>(k)], scores[static_cast<std::size_t>(k)]});
  }
  std::sort(people.begin(), people.end(),
            [](const PersonBox& a, const PersonBox& b) { return a.confidence > b.confidence; });
  return people;
}

}  // namespace hbos::slam
