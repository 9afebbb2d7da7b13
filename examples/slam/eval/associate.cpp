#include "eval/associate.hpp"

#include <hbos/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <tuple>

namespace hbos::slam {

namespace {

void check_stamps(const std::vector<double>& stamps, const char* which) {
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    detail::require(std::isfinite(stamps[i]), "associate: ", which, " stamp ", i,
                    " is not finite: ", stamps[i]);
    detail::require(i == 0 || stamps[i] > stamps[i - 1], "associate: ", which,
                    " stamps must strictly increase, but stamp ", i, " = ", stamps[i], " follows ",
                    stamps[i == 0 ? 0 : i - 1]);
  }
}

struct Candidate {
  double difference;
  std::size_t gt;
  std::size_t est;
};

}  // namespace

std::vector<Match> associate(const std::vector<double>& gt_stamps,
                             const std::vector<double>& est_stamps,
                             const AssociationParams& params) {
  detail::require(std::isfinite(params.max_difference) && params.max_difference >= 0.0,
                  "associate: max_difference must be finite and >= 0, got ", params.max_difference);
  detail::require(std::isfinite(params.offset), "associate: offset must be finite, got ",
                  params.offset);
  check_stamps(gt_stamps, "ground-truth");
  check_stamps(est_stamps, "estimate");

  // For a fixed ground-truth stamp a, |a − (b + offset)| falls and then rises along the sorted
  // estimate stamps b (b + offset is monotone in floating point too), so the candidates of a
  // form one contiguous run around the first b with b + offset >= a. Walking out from there
  // with the script's exact predicate finds the same candidates as its double loop.
  const double offset = params.offset;
  const auto within = [&](double a, double b) {
    return std::abs(a - (b + offset)) < params.max_difference;
  };
  std::vector<Candidate> candidates;
  for (std::size_t g = 0; g < gt_stamps.size(); ++g) {
    const double a = gt_stamps[g];
    const auto pivot = std::partition_point(est_stamps.begin(), est_stamps.end(),
                                            [&](double b) { return b + offset < a; });
    const auto p = static_cast<std::size_t>(pivot - est_stamps.begin());
    for (std::size_t e = p; e < est_stamps.size() && within(a, est_stamps[e]); ++e) {
      candidates.push_back({std::abs(a - (est_stamps[e] + offset)), g, e});
    }
    for (std::size_t e = p; e > 0 && within(a, est_stamps[e - 1]); --e) {
      candidates.push_back({std::abs(a - (est_stamps[e - 1] + offset)), g, e - 1});
    }
  }
  // associate.py sorts (|Δ|, a, b) tuples; stamps strictly increase, so indices order like
  // stamps.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    return std::tie(x.difference, x.gt, x.est) < std::tie(y.difference, y.gt, y.est);
  });

  std::vector<bool> gt_taken(gt_stamps.size(), false);
  std::vector<bool> est_taken(est_stamps.size(), false);
  std::vector<Match> matches;
  for (const Candidate& c : candidates) {
    if (gt_taken[c.gt] || est_taken[c.est]) continue;
    gt_taken[c.gt] = true;
    est_taken[c.est] = true;
    matches.push_back({static_cast<Eigen::Index>(c.gt), static_cast<Eigen::Index>(c.est)});
  }
  std::sort(matches.begin(), matches.end(),
            [](const Match& x, const Match& y) { return x.gt < y.gt; });
  return matches;
}

std::vector<Match> associate(const Trajectory& gt, const Trajectory& est,
                             const AssociationParams& params) {
  return associate(gt.stamps, est.stamps, params);
}

}  // namespace hbos::slam
