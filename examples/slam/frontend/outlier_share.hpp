#pragma once
/// \file
/// The forgetting-weighted share of a point's screenings that rejected it:
///   share = sum_k lambda^k r_k / sum_k lambda^k,   r_k = 1 if screened out k screenings ago,
/// kept as two running sums (num <- lambda num + r, den <- lambda den + 1). It lies in [0, 1],
/// is 0 for a point never screened, and is what MatchEvidence::outlier_history carries to the
/// screen (residual_screen.hpp). Both trackers keep one per point they follow: the map tracker
/// per map point, the frame tracker per keypoint along its chain of frame-to-frame matches.

namespace hbos::slam {

class OutlierShare {
 public:
  /// Records one screening: `rejected` = screened out; `forgetting` in [0, 1] is the weight the
  /// past keeps per screening.
  void record(bool rejected, double forgetting) {
    weighted_rejections_ = forgetting * weighted_rejections_ + (rejected ? 1.0 : 0.0);
    weighted_screenings_ = forgetting * weighted_screenings_ + 1.0;
  }

  /// [0, 1]; 0 when never screened.
  [[nodiscard]] double share() const {
    return weighted_screenings_ > 0.0 ? weighted_rejections_ / weighted_screenings_ : 0.0;
  }

  /// The forgetting-weighted number of screenings: 0 for a point never screened, at most
  /// 1 / (1 - forgetting).
  [[nodiscard]] double screenings() const { return weighted_screenings_; }

  /// How far the screenings vouch for the point as static: its forgetting-weighted kept
  /// screenings over screenings + 1, in [0, 1). The 1 is a prior screening that rejected it, so
  /// a point never screened has no trust (0) where its share would say "never rejected", and
  /// trust grows with each screening that kept it.
  [[nodiscard]] double static_trust() const {
    return (weighted_screenings_ - weighted_rejections_) / (weighted_screenings_ + 1.0);
  }

 private:
  double weighted_rejections_ = 0.0;
  double weighted_screenings_ = 0.0;
};

}  // namespace hbos::slam
