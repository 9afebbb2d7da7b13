#include "case_builder.hpp"

#include "frontend/frame.hpp"
#include "frontend/frame_matching.hpp"
#include "frontend/orb_extraction.hpp"
#include "frontend/person_mask.hpp"
#include "frontend/rough_pose.hpp"
#include "ground_truth.hpp"

#include <fmt/format.h>
#include <hbos/error.hpp>
#include <hbos/screening/matches.hpp>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

namespace hbos::cases {

namespace {

// The front end's settings, written out so that the cases do not change when its defaults do.
hbos::slam::ExtractionConfig extraction_settings() {
  hbos::slam::ExtractionConfig c;
  c.features = 1000;
  c.scale_factor = 1.2f;
  c.levels = 8;
  c.fast_threshold = 20;
  c.min_fast_threshold = 7;
  c.min_depth_m = 0.1;
  c.max_depth_m = 8.0;
  return c;
}
hbos::slam::MatchingConfig matching_settings() {
  hbos::slam::MatchingConfig c;
  c.max_hamming = 50;
  c.cross_check = true;
  c.ratio = 0.0;
  return c;
}
hbos::slam::RoughPoseConfig ransac_settings() {
  hbos::slam::RoughPoseConfig c;
  c.method = hbos::slam::RoughPoseMethod::kRansac;
  c.ransac_threshold_px = 1.0;
  c.ransac_iterations = 300;
  c.ransac_confidence = 0.999;
  c.min_inliers = 12;
  return c;
}

// One frame as the pair builder needs it.
struct FrameData {
  int index = 0;
  double stamp = 0.0;
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
  hbos::slam::Features features;
  cv::Mat mask_distance;   // CV_32F [px]; empty = no masked pixel in this frame
  std::vector<int> track;  // chain id per feature, -1 = not linked yet
};

cv::Mat case_mask(const CaseSpec& spec, const cv::Mat& label, int index) {
  if (spec.mask == MaskKind::kNone || label.empty()) return {};
  if (spec.mask == MaskKind::kExact) return label != 0;
  hbos::slam::MaskConfig config;
  config.source = hbos::slam::MaskSource::kDegraded;
  config.degraded_erosion_px = spec.degradation.erosion_px;
  config.degraded_unmasked_lower = spec.degradation.unmasked_lower;
  config.degraded_missing_every = spec.degradation.missing_every;
  // Each person degraded on its own (its own lower body), then united.
  cv::Mat mask(label.size(), CV_8UC1, cv::Scalar(0));
  for (std::size_t k = 0; k < spec.people.size(); ++k) {
    const cv::Mat one = label == static_cast<int>(k + 1);
    if (cv::countNonZero(one) == 0) continue;
    mask |= hbos::slam::degrade_mask(one, index, config);
  }
  return mask;
}

FrameData load_frame(const CaseSpec& spec, const CaseInputs& in, const MovingPeople* people,
                     hbos::slam::OrbExtractor& extractor, int index, cv::Mat* preview = nullptr) {
  FrameData f;
  f.index = index;
  f.stamp = in.sequence.frames[static_cast<std::size_t>(index)].rgb.stamp;
  f.T_world_camera = interpolate_pose(*in.sequence.groundtruth, f.stamp);
  hbos::slam::RgbdImages images =
      hbos::slam::read_frame_images(in.sequence, index, in.camera.depth_factor);
  hbos::slam::Frame frame;
  frame.index = index;
  frame.stamp = f.stamp;
  frame.bgr = std::move(images.bgr);
  frame.depth_m = std::move(images.depth_m);
  if (people != nullptr)
    frame.person_label = people->composite(f.stamp, f.T_world_camera, frame.bgr, frame.depth_m);
  frame.mask = case_mask(spec, frame.person_label, index);
  f.features = extractor.extract(frame);
  if (preview != nullptr) {
    cv::Mat view = frame.bgr.clone();
    if (!frame.mask.empty()) view.setTo(cv::Scalar(0, 0, 255), frame.mask);
    cv::addWeighted(view, 0.35, frame.bgr, 0.65, 0.0, view);
    if (!frame.person_label.empty()) {
      std::vector<std::vector<cv::Point>> outline;
      cv::findContours(frame.person_label != 0, outline, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
      cv::drawContours(view, outline, -1, cv::Scalar(0, 255, 0), 1);
    }
    for (const cv::KeyPoint& k : f.features.keypoints)
      cv::circle(view, k.pt, 2, cv::Scalar(0, 255, 255), 1);
    *preview = view;
  }
  if (!frame.mask.empty() && cv::countNonZero(frame.mask) > 0) {
    cv::distanceTransform(frame.mask == 0, f.mask_distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  }
  f.track.assign(f.features.size(), -1);
  return f;
}

// The ground truth refined on the static matches. TUM's motion-capture poses are a few
// millimetres / tenths of a degree off the camera (time offset, calibration): up to 1.6 px/sigma
// median static residual on fr1/xyz. Labels need the pose the static matches agree on: start at
// the ground truth, keep the static matches within 4, then 3 sigma, refine with
// Levenberg-Marquardt (cv::solvePnPRefineLM), repeat. Fewer than 12 such matches: ground truth.
Eigen::Isometry3d reference_pose(const Eigen::Isometry3d& T_gt,
                                 const std::vector<Eigen::Vector3d>& points,
                                 const std::vector<Eigen::Vector2d>& observed,
                                 const std::vector<double>& sigma,
                                 const std::vector<std::uint8_t>& is_static,
                                 const hbos::PinholeCamerad& camera, int& used) {
  Eigen::Isometry3d T = T_gt;
  used = 0;
  const cv::Matx33d K(camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0);
  for (const double gate : {4.0, 3.0, 3.0, 3.0}) {
    std::vector<cv::Point3d> object;
    std::vector<cv::Point2d> image;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (is_static[i] == 0) continue;
      const Eigen::Vector3d p = T * points[i];
      if (p.z() <= 0.0 || (observed[i] - camera.project(p)).norm() > gate * sigma[i]) continue;
      object.emplace_back(points[i].x(), points[i].y(), points[i].z());
      image.emplace_back(observed[i].x(), observed[i].y());
    }
    if (object.size() < 12) return used == 0 ? T_gt : T;
    cv::Mat R_cv, rvec, tvec;
    cv::eigen2cv(Eigen::Matrix3d(T.linear()), R_cv);
    cv::Rodrigues(R_cv, rvec);
    cv::eigen2cv(Eigen::Vector3d(T.translation()), tvec);
    cv::solvePnPRefineLM(object, image, K, cv::noArray(), rvec, tvec);
    cv::Rodrigues(rvec, R_cv);
    Eigen::Matrix3d R;
    Eigen::Vector3d t;
    cv::cv2eigen(R_cv, R);
    cv::cv2eigen(tvec, t);
    T.linear() = R;
    T.translation() = t;
    used = static_cast<int>(object.size());
  }
  return T;
}

}  // namespace

std::vector<PairRecord> build_case(const CaseSpec& spec, const CaseInputs& in) {
  if (!in.sequence.groundtruth) {
    throw InvalidArgument(fmt::format("sequence '{}' has no groundtruth.txt", in.sequence.root));
  }
  if (in.sequence.size() < 2) {
    throw InvalidArgument(fmt::format("sequence '{}' has fewer than 2 frames", in.sequence.root));
  }
  const hbos::PinholeCamerad camera = in.camera.pinhole();
  hbos::slam::OrbExtractor extractor(extraction_settings(), in.camera);
  const hbos::slam::FrameMatcher matcher(matching_settings());
  const hbos::slam::RoughPoseEstimator ransac(ransac_settings(), camera);

  const int n = static_cast<int>(in.sequence.size());
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) order[static_cast<std::size_t>(i)] = spec.reverse ? n - 1 - i : i;
  const int first = order.front();
  const double first_stamp = in.sequence.frames[static_cast<std::size_t>(first)].rgb.stamp;
  std::optional<MovingPeople> people;
  if (!spec.people.empty()) {
    people.emplace(in.people, spec.people, camera,
                   interpolate_pose(*in.sequence.groundtruth, first_stamp), first_stamp);
  }

  SplitMix64 random(spec.seed);
  Eigen::Isometry3d velocity = Eigen::Isometry3d::Identity();
  int next_track = 0;
  std::vector<PairRecord> pairs;
  FrameData prev = load_frame(spec, in, people ? &*people : nullptr, extractor, first);
  for (std::size_t k = 1; k < order.size(); ++k) {
    FrameData cur = load_frame(spec, in, people ? &*people : nullptr, extractor, order[k]);
    const std::vector<hbos::slam::FeatureMatch> matches =
        matcher.match(prev.features, cur.features);
    std::vector<Eigen::Vector3d> points;
    std::vector<Eigen::Vector2d> observed;
    std::vector<double> sigma;
    std::vector<std::uint8_t> is_static;
    for (const auto& m : matches) {
      const auto p = static_cast<std::size_t>(m.previous), c = static_cast<std::size_t>(m.current);
      points.push_back(camera.back_project(prev.features.undistorted[p],
                                           static_cast<double>(prev.features.depth_m[p])));
      observed.push_back(cur.features.undistorted[c]);
      sigma.push_back(hbos::sigma_from_octave(cur.features.keypoints[c].octave));
      is_static.push_back(prev.features.on_person[p] == 0 && cur.features.on_person[c] == 0);
    }
    const Eigen::Isometry3d T_gt = cur.T_world_camera.inverse() * prev.T_world_camera;

    PairRecord pair;
    pair.prev_frame = prev.index;
    pair.cur_frame = cur.index;
    pair.prev_stamp = prev.stamp;
    pair.cur_stamp = cur.stamp;
    const Eigen::Isometry3d T_true =
        reference_pose(T_gt, points, observed, sigma, is_static, camera, pair.reference_matches);
    const hbos::slam::RoughPose rough = ransac.estimate(points, observed, velocity);
    const Eigen::Isometry3d& T_ransac = rough.T_cur_prev;
    velocity = T_ransac;
    pair.ransac_ok = rough.from_ransac;
    pair.ransac_inliers = rough.ransac_inliers;
    const Eigen::Isometry3d T_perturbed = perturb(T_true, spec.perturb_deg, spec.perturb_m, random);
    const PoseError e_ransac = pose_error(T_ransac, T_true);
    const PoseError e_perturbed = pose_error(T_perturbed, T_true);
    const PoseError e_gt = pose_error(T_gt, T_true);
    pair.ransac_rotation_error_deg = e_ransac.rotation_deg;
    pair.ransac_translation_error_m = e_ransac.translation_m;
    pair.perturbed_rotation_error_deg = e_perturbed.rotation_deg;
    pair.perturbed_translation_error_m = e_perturbed.translation_m;
    pair.gt_rotation_error_deg = e_gt.rotation_deg;
    pair.gt_translation_error_m = e_gt.translation_m;

    for (std::size_t i = 0; i < matches.size(); ++i) {
      const auto p = static_cast<std::size_t>(matches[i].previous);
      const auto c = static_cast<std::size_t>(matches[i].current);
      MatchRow row;
      row.observed = observed[i];
      const Eigen::Vector3d in_ransac = T_ransac * points[i];
      const Eigen::Vector3d in_perturbed = T_perturbed * points[i];
      const Eigen::Vector3d in_true = T_true * points[i];
      // A point behind a camera cannot be predicted (never seen on these sequences).
      if (in_ransac.z() <= 0.0 || in_perturbed.z() <= 0.0 || in_true.z() <= 0.0) continue;
      row.ransac = camera.project(in_ransac);
      row.perturbed = camera.project(in_perturbed);
      row.reference = camera.project(in_true);
      const cv::KeyPoint& key = cur.features.keypoints[c];
      row.octave = key.octave;
      row.depth_m = cur.features.depth_m[c];
      row.prev_depth_m = prev.features.depth_m[p];
      if (spec.mask != MaskKind::kNone) row.mask_distance_px = kNoMaskPixel;
      if (!cur.mask_distance.empty()) {
        const int x =
            std::clamp(static_cast<int>(std::lround(key.pt.x)), 0, cur.mask_distance.cols - 1);
        const int y =
            std::clamp(static_cast<int>(std::lround(key.pt.y)), 0, cur.mask_distance.rows - 1);
        row.mask_distance_px = static_cast<double>(cur.mask_distance.at<float>(y, x));
        row.on_mask = row.mask_distance_px <= kOnMaskPx;
      }
      row.dynamic = is_static[i] == 0;
      row.gross = !row.dynamic && (row.observed - row.reference).norm() > kGrossSigmas * sigma[i];
      if (prev.track[p] < 0) prev.track[p] = next_track++;
      row.track_id = prev.track[p];
      cur.track[c] = prev.track[p];
      pair.rows.push_back(row);
    }
    pairs.push_back(std::move(pair));
    prev = std::move(cur);
  }
  return pairs;
}

cv::Mat preview_frame(const CaseSpec& spec, const CaseInputs& in, int index) {
  if (index < 0 || index >= in.sequence.size()) {
    throw InvalidArgument(
        fmt::format("preview frame {} out of range [0, {})", index, in.sequence.size()));
  }
  hbos::slam::OrbExtractor extractor(extraction_settings(), in.camera);
  const int n = static_cast<int>(in.sequence.size());
  const int first = spec.reverse ? n - 1 : 0;
  const double first_stamp = in.sequence.frames[static_cast<std::size_t>(first)].rgb.stamp;
  std::optional<MovingPeople> people;
  if (!spec.people.empty()) {
    people.emplace(in.people, spec.people, in.camera.pinhole(),
                   interpolate_pose(*in.sequence.groundtruth, first_stamp), first_stamp);
  }
  cv::Mat view;
  static_cast<void>(load_frame(spec, in, people ? &*people : nullptr, extractor, index, &view));
  return view;
}

}  // namespace hbos::cases
