#pragma once
/// \file
/// The screen's memory of one map point. Frame-to-frame odometry forgets what the screen
/// rejected, so a person's point that leaked once is new again next frame; a map point instead
/// remembers how often it was screened out and is culled when it keeps being rejected.
///
/// outlier_share() is the forgetting-weighted share of the point's screenings that rejected it:
///   share = sum_k lambda^k r_k / sum_k lambda^k,   r_k = 1 if screened out k screenings ago,
/// kept as two running sums (num <- lambda num + r, den <- lambda den + 1). It lies in [0, 1],
/// is 0 for a point never screened, and is what MatchEvidence::outlier_history carries to the
/// screen (residual_screen.hpp).

#include "frontend/map/map_config.hpp"

namespace hbos::slam {

class ScreeningHistory {
 public:
  /// Records one screening of the point: `rejected` = screened out.
  void record(bool rejected, double forgetting) {
    weighted_rejections_ = forgetting * weighted_rejections_ + (rejected ? 1.0 : 0.0);
    weighted_screenings_ = forgetting * weighted_screenings_ + 1.0;
    consecutive_rejections_ = rejected ? consecutive_rejections_ + 1 : 0;
    ++screenings_;
  }

  /// [0, 1] forgetting-weighted share of screenings that rejected the point; 0 when never
  /// screened.
  [[nodiscard]] double outlier_share() const {
    return weighted_screenings_ > 0.0 ? weighted_rejections_ / weighted_screenings_ : 0.0;
  }
  [[nodiscard]] int consecutive_rejections() const { return consecutive_rejections_; }
  [[nodiscard]] int screenings() const { return screenings_; }

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

 private:
  double weighted_rejections_ = 0.0;
  double weighted_screenings_ = 0.0;
  int consecutive_rejections_ = 0;
  int screenings_ = 0;
};

}  // namespace hbos::slam
