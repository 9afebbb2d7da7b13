#pragma once
/// \file
/// Builds one labelled residual case: every frame of the sequence with the case's people
/// composited and moving, ORB extracted outside the case's mask, frame-to-frame matches, the
/// rough pose, and per match the predicted and observed pixels with the labels.

#include "case_spec.hpp"
#include "frontend/camera.hpp"
#include "frontend/dataset.hpp"

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace hbos::cases {

/// A match is `gross` when it is static and its residual under the reference pose exceeds this
/// many sigma (sigma = 1.2^octave px): 6x the measured 0.5 px x sigma keypoint noise. The
/// reference pose is the ground truth refined on the static matches (see reference_pose).
inline constexpr double kGrossSigmas = 3.0;
/// A match is `on_mask` when its observed keypoint lies within this distance of a masked pixel
/// [px]: the radius of ORB's 31 px descriptor patch at level 0, so the descriptor saw the mask.
inline constexpr double kOnMaskPx = 15.0;

inline constexpr double kNoMaskPixel = std::numeric_limits<double>::infinity();

/// One match of a pair. Pixels are undistorted [px]; the mask distance is on the recorded
/// (distorted) image, where the mask is.
struct MatchRow {
  Eigen::Vector2d ransac;     ///< [px] previous keypoint back-projected, moved by the RANSAC pose
  Eigen::Vector2d perturbed;  ///< [px] the same under the perturbed reference pose
  Eigen::Vector2d observed;   ///< [px] the current keypoint
  Eigen::Vector2d reference;  ///< [px] the same prediction under the reference pose
  int octave = 0;             ///< of the current keypoint
  float depth_m = 0.f;        ///< [m] at the current keypoint, 0 = none
  float prev_depth_m = 0.f;   ///< [m] at the previous keypoint (> 0: it was back-projected)
  /// [px] to the nearest masked pixel; -1 = the scene has no mask, kNoMaskPixel = it has one but
  /// this frame's is empty (the degraded mask's missed detections)
  double mask_distance_px = -1.0;
  bool on_mask = false;  ///< 0 <= mask_distance_px <= kOnMaskPx
  bool dynamic = false;  ///< either keypoint on a composited person (exact label)
  bool gross = false;    ///< static and |observed - reference| > kGrossSigmas sigma
  int track_id = -1;     ///< the previous keypoint's chain over the case's frames
};

/// One frame pair and its rough poses. Pose errors are against the reference pose.
struct PairRecord {
  int prev_frame = 0;  ///< index into the sequence
  int cur_frame = 0;
  double prev_stamp = 0.0;  ///< [s]
  double cur_stamp = 0.0;   ///< [s]
  bool ransac_ok = false;   ///< RANSAC succeeded (else the constant-velocity fallback was used)
  int ransac_inliers = 0;
  double ransac_rotation_error_deg = 0.0;
  double ransac_translation_error_m = 0.0;
  double perturbed_rotation_error_deg = 0.0;  ///< = the case's perturbation, by construction
  double perturbed_translation_error_m = 0.0;
  double gt_rotation_error_deg = 0.0;  ///< raw ground truth vs the reference (its refinement)
  double gt_translation_error_m = 0.0;
  int reference_matches = 0;  ///< static matches the reference was refined on
  std::vector<MatchRow> rows;
};

/// What every case shares: the sequence (with ground truth), the camera and the source people.
struct CaseInputs {
  hbos::slam::RgbdSequence sequence;
  hbos::slam::CameraModel camera;
  std::vector<SourcePerson> people;
};

/// Builds the case. Deterministic: the same inputs give the same rows (OpenCV's RANSAC seeds its
/// own generator; the perturbation uses the case's seed). Throws hbos::InvalidArgument on bad
/// specs or inputs.
[[nodiscard]] std::vector<PairRecord> build_case(const CaseSpec& spec, const CaseInputs& inputs);

/// The composited frame `index` of the case with its mask (red tint), person label (green
/// outline) and ORB keypoints (yellow), for inspecting a grid point. 8-bit BGR.
[[nodiscard]] cv::Mat preview_frame(const CaseSpec& spec, const CaseInputs& inputs, int index);

}  // namespace hbos::cases
