#include "render/masks.hpp"

#include <algorithm>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "render/random.hpp"

namespace hbos::render {

const std::vector<std::string>& mask_variant_names() {
  static const std::vector<std::string> names = {"perfect",         "eroded",       "dilated",
                                                 "missing",         "delayed",      "boxes",
                                                 "object_unmasked", "person_missed"};
  return names;
}

MaskPlan MaskPlan::make(std::uint64_t seed, int frame_count, int people,
                        std::vector<int> carried_ids) {
  MaskPlan p;
  p.seed = seed;
  p.frame_count = frame_count;
  p.carried_ids = std::move(carried_ids);
  Rng missing = stream(seed, Stream::kMaskMissing);
  for (int i = 0; i < frame_count; ++i) {
    if (missing.uniform() < p.missing_rate) p.missing_frames.push_back(i);
  }
  Rng missed = stream(seed, Stream::kMaskPersonMissed);
  p.missed_person =
      people > 0 ? 1 + static_cast<int>(missed.below(static_cast<std::uint64_t>(people))) : 0;
  const int len = std::min(frame_count, std::max(15, frame_count / 4));
  const int room = frame_count - len;
  p.missed_first =
      room > 0 ? static_cast<int>(missed.below(static_cast<std::uint64_t>(room) + 1)) : 0;
  p.missed_last = p.missed_first + len - 1;
  return p;
}

cv::Mat perfect_mask(const cv::Mat& ids) {
  cv::Mat m(ids.size(), CV_8U, cv::Scalar(kMaskStatic));
  m.setTo(kMaskDynamic, ids != 0);
  return m;
}

namespace {

// The dynamic region as 255 (OpenCV's morphology works on the foreground).
cv::Mat dynamic_of(const cv::Mat& ids) { return ids != 0; }

cv::Mat to_mask(const cv::Mat& dynamic) {
  cv::Mat m(dynamic.size(), CV_8U, cv::Scalar(kMaskStatic));
  m.setTo(kMaskDynamic, dynamic);
  return m;
}

cv::Mat disc(int radius) {
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1));
}

int radius(std::uint64_t seed, Stream s, int frame, int lo, int hi) {
  Rng r = stream(seed, s, static_cast<std::uint64_t>(frame));
  return lo + static_cast<int>(r.below(static_cast<std::uint64_t>(hi - lo + 1)));
}

}  // namespace

cv::Mat make_mask(const std::string& variant, const MaskPlan& plan, int frame, const cv::Mat& ids,
                  const cv::Mat& previous_ids) {
  if (variant == "perfect") return perfect_mask(ids);
  if (variant == "eroded") {
    cv::Mat d;
    cv::erode(
        dynamic_of(ids), d,
        disc(radius(plan.seed, Stream::kMaskEroded, frame, plan.erode_min_px, plan.erode_max_px)),
        cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
    return to_mask(d);
  }
  if (variant == "dilated") {
    cv::Mat d;
    cv::dilate(dynamic_of(ids), d,
               disc(radius(plan.seed, Stream::kMaskDilated, frame, plan.dilate_min_px,
                           plan.dilate_max_px)),
               cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
    return to_mask(d);
  }
  if (variant == "missing") {
    if (std::binary_search(plan.missing_frames.begin(), plan.missing_frames.end(), frame)) {
      return cv::Mat(ids.size(), CV_8U, cv::Scalar(kMaskStatic));
    }
    return perfect_mask(ids);
  }
  if (variant == "delayed") {
    if (previous_ids.empty()) return cv::Mat(ids.size(), CV_8U, cv::Scalar(kMaskStatic));
    return perfect_mask(previous_ids);
  }
  if (variant == "boxes") {
    cv::Mat m(ids.size(), CV_8U, cv::Scalar(kMaskStatic));
    double max_id = 0;
    cv::minMaxLoc(ids, nullptr, &max_id);
    for (int id = 1; id <= static_cast<int>(max_id); ++id) {
      const cv::Mat sel = ids == id;
      if (cv::countNonZero(sel) == 0) continue;
      m(cv::boundingRect(sel)).setTo(kMaskDynamic);
    }
    return m;
  }
  if (variant == "object_unmasked") {
    cv::Mat dyn = dynamic_of(ids);
    for (int id : plan.carried_ids) dyn.setTo(0, ids == id);
    return to_mask(dyn);
  }
  if (variant == "person_missed") {
    cv::Mat dyn = dynamic_of(ids);
    if (frame >= plan.missed_first && frame <= plan.missed_last)
      dyn.setTo(0, ids == plan.missed_person);
    return to_mask(dyn);
  }
  throw std::invalid_argument("unknown mask variant '" + variant + "'");
}

}  // namespace hbos::render
