#pragma once
/// \file
/// The screen's memory of one map point. Frame-to-frame odometry forgets what the screen
/// rejected, so a person's point that leaked once is new again next frame; a map point instead
/// remembers how often it was screened out and is culled when it keeps being rejected.
///
/// outlier_share() is the forgetting-weighted share of the point's screenings that rejected it
/// (frontend/outlier_share.hpp).

#include "frontend/map/map_config.hpp"
#include "frontend/outlier_share.hpp"

namespace hbos::slam {

class ScreeningHistory {
 public:
  /// Records one screening of the point: `rejected` = screened out.
  void record(bool rejected, double forgetting) {
    share_.record(rejected, forgetting);
    consecutive_rejections_ = rejected ? consecutive_rejections_ + 1 : 0;
    ++screenings_;
    kept_ += rejected ? 0 : 1;
  }

  /// [0, 1] forgetting-weighted share of screenings that rejected the point; 0 when never
  /// screened.
  [[nodiscard]] double outlier_share() const { return share_.share(); }
  [[nodiscard]] int consecutive_rejections() const { return consecutive_rejections_; }
  [[nodiscard]] int screenings() const { return screenings_; }
  /// Screenings that kept the point.
  [[nodiscard]] int kept() const { return kept_; }

  /// Screened out again and again: `cull_consecutive` times in a row, or an outlier share of at
  /// least `cull_share` over `cull_min_screenings` screenings or more.
  [[nodiscard]] bool should_cull(const HistoryConfig& c) const {
    return consecutive_rejections_ >= c.cull_consecutive ||
           (screenings_ >= c.cull_min_screenings && outlier_share() >= c.cull_share);
  }

  /// Too suspicious to help build the rough pose (it is still matched and screened).
  [[nodiscard]] bool distrusted(const HistoryConfig& c) const {
    return screenings_ >= 2 && outlier_share() > c.rough_pose_max_share;
  }

  /// Out of probation: kept by the screen `probation_kept` times. A point a keyframe has just
  /// made from a keypoint nobody checked (a person the mask missed is the nearest thing in view,
  /// and new points are taken nearest first) has not yet shown that it moves with the map.
  [[nodiscard]] bool proven(const HistoryConfig& c) const { return kept_ >= c.probation_kept; }

 private:
  OutlierShare share_;
  int consecutive_rejections_ = 0;
  int screenings_ = 0;
  int kept_ = 0;
};

}  // namespace hbos::slam
