#include "eval/rpe.hpp"

#include <hbos/error.hpp>
#include "common/index.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

namespace hbos::slam {

namespace {

using examples::at;

// The "position" along the estimate that delta is measured in, one value per estimate pose,
// non-decreasing.
std::vector<double> delta_axis(const Trajectory& gt, const Trajectory& est,
                               const RpeParams& params) {
  std::vector<double> axis(est.stamps.size());
  switch (params.unit) {
    case RpeDeltaUnit::kSeconds:
      axis = est.stamps;
      break;
    case RpeDeltaUnit::kFrames:
      for (std::size_t i = 0; i < axis.size(); ++i) axis[i] = static_cast<double>(i);
      break;
    case RpeDeltaUnit::kMetresAlongGt: {
      std::vector<double> travelled(gt.stamps.size(), 0.0);
      for (Eigen::Index k = 1; k < gt.size(); ++k) {
        travelled[at(k)] =
            travelled[at(k - 1)] + (gt.positions.col(k) - gt.positions.col(k - 1)).norm();
      }
      for (std::size_t i = 0; i < axis.size(); ++i) {
        axis[i] = travelled[at(find_closest_index(gt.stamps, est.stamps[i] + params.offset))];
      }
      break;
    }
  }
  return axis;
}

void check_params(const RpeParams& params) {
  detail::require(std::isfinite(params.delta) && params.delta > 0.0,
                  "compute_rpe: delta must be finite and > 0, got ", params.delta);
  detail::require(params.unit != RpeDeltaUnit::kFrames || std::floor(params.delta) == params.delta,
                  "compute_rpe: a delta in frames must be a whole number, got ", params.delta);
  detail::require(std::isfinite(params.offset), "compute_rpe: offset must be finite, got ",
                  params.offset);
  detail::require(std::isfinite(params.est_scale) && params.est_scale > 0.0,
                  "compute_rpe: est_scale must be finite and > 0, got ", params.est_scale);
}

}  // namespace

Eigen::Index find_closest_index(const std::vector<double>& values, double t) {
  detail::require(!values.empty(), "find_closest_index: empty list");
  std::size_t begin = 0;
  std::size_t end = values.size();
  std::size_t best = 0;
  double best_difference = std::abs(values[0] - t);
  while (begin < end) {
    const std::size_t middle = (begin + end) / 2;
    const double difference = std::abs(values[middle] - t);
    if (difference < best_difference) {
      best_difference = difference;
      best = middle;
    }
    if (t == values[middle]) return static_cast<Eigen::Index>(middle);
    if (values[middle] > t) {
      end = middle;
    } else {
      begin = middle + 1;
    }
  }
  return static_cast<Eigen::Index>(best);
}

RpeResult compute_rpe(const Trajectory& gt, const Trajectory& est, const RpeParams& params) {
  check_trajectory(gt, "compute_rpe: ground truth");
  check_trajectory(est, "compute_rpe: estimate");
  check_params(params);
  detail::require(gt.size() >= 2 && est.size() >= 2, "compute_rpe: needs at least 2 poses in ",
                  "each trajectory, got ", gt.size(), " ground-truth and ", est.size(),
                  " estimate poses");
  const std::vector<double>& sg = gt.stamps;
  const std::vector<double>& se = est.stamps;
  const double offset = params.offset;

  // The script's sanity check: map each estimate stamp to its nearest ground-truth stamp and
  // back; if that reaches fewer than 2 distinct estimate poses, the two do not overlap in time.
  std::vector<bool> reached(se.size(), false);
  Eigen::Index n_reached = 0;
  for (const double t : se) {
    const double t_gt = sg[at(find_closest_index(sg, t + offset))];
    const std::size_t back = at(find_closest_index(se, t_gt - offset));
    if (!reached[back]) ++n_reached;
    reached[back] = true;
  }
  detail::require(n_reached >= 2, "compute_rpe: '", est.name, "' and '", gt.name,
                  "' hardly overlap in time (wrong files, or a stamp offset?)");

  RpeResult result;
  result.n_gt_poses = gt.size();
  result.n_est_poses = est.size();

  // 1. Candidate pairs (i, j).
  const std::vector<double> axis = delta_axis(gt, est, params);
  // Beyond the whole span no pair exists; far beyond it (1e16 s), axis[i] + delta rounds to the
  // same number for every i and the closest index came out as 0: every pair (i, 0), exit 0.
  detail::require(params.delta <= axis.back() - axis.front(), "compute_rpe: the delta ",
                  params.delta, " exceeds the whole span of '", est.name, "' (",
                  axis.back() - axis.front(), " in the delta's unit)");
  std::vector<std::pair<std::size_t, std::size_t>> candidates;
  for (std::size_t i = 0; i < axis.size(); ++i) {
    const auto j = at(find_closest_index(axis, axis[i] + params.delta));
    if (j != axis.size() - 1) candidates.emplace_back(i, j);
  }
  result.n_candidates = static_cast<Eigen::Index>(candidates.size());
  result.n_candidates_with_i_equal_j = static_cast<Eigen::Index>(
      std::count_if(candidates.begin(), candidates.end(),
                    [](const auto& pair) { return pair.first == pair.second; }));

  // 2. The ground-truth tolerance: twice the median ground-truth period.
  Eigen::VectorXd periods(gt.size() - 1);
  for (Eigen::Index k = 0; k + 1 < gt.size(); ++k) periods(k) = sg[at(k + 1)] - sg[at(k)];
  result.gt_max_time_difference = 2.0 * compute_statistics(periods).median;

  // 3. Errors.
  for (const auto& [i, j] : candidates) {
    const double t0 = se[i] + offset;
    const double t1 = se[j] + offset;
    const Eigen::Index g0 = find_closest_index(sg, t0);
    const Eigen::Index g1 = find_closest_index(sg, t1);
    if (std::abs(sg[at(g0)] - t0) > result.gt_max_time_difference ||
        std::abs(sg[at(g1)] - t1) > result.gt_max_time_difference) {
      continue;
    }
    const auto ei = static_cast<Eigen::Index>(i);
    const auto ej = static_cast<Eigen::Index>(j);
    Eigen::Isometry3d est_motion = est.pose(ej).inverse(Eigen::Isometry) * est.pose(ei);
    est_motion.translation() *= params.est_scale;
    const Eigen::Isometry3d gt_motion = gt.pose(g1).inverse(Eigen::Isometry) * gt.pose(g0);
    const Eigen::Isometry3d error = est_motion.inverse(Eigen::Isometry) * gt_motion;

    RpePair pair;
    pair.est0 = ei;
    pair.est1 = ej;
    pair.gt0 = g0;
    pair.gt1 = g1;
    pair.trans_error = error.translation().norm();
    const Eigen::Matrix3d& r = error.linear();
    const double cosine = (r(0, 0) + r(1, 1) + r(2, 2) - 1.0) / 2.0;
    pair.rot_error = std::acos(std::min(1.0, std::max(-1.0, cosine)));
    if (i == j) ++result.n_pairs_with_i_equal_j;
    result.pairs.push_back(pair);
  }
  detail::require(result.pairs.size() >= 2, "compute_rpe: only ", result.pairs.size(),
                  " pose pairs have ground truth within ", result.gt_max_time_difference,
                  " s at both ends (of ", candidates.size(),
                  " candidates); need at least 2 (delta too large for the sequence?)");

  const auto n = static_cast<Eigen::Index>(result.pairs.size());
  Eigen::VectorXd trans(n);
  Eigen::VectorXd rot(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    trans(k) = result.pairs[at(k)].trans_error;
    rot(k) = result.pairs[at(k)].rot_error;
  }
  result.trans_m = compute_statistics(trans);
  result.rot_deg = compute_statistics(rot).radians_to_degrees();
  return result;
}

}  // namespace hbos::slam
