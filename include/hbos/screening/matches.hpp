#pragma once
/// \file
/// The input of reprojection screening: one frame's matches.
///
/// A match i pairs a **predicted** pixel p_i (a map point or previous-frame point reprojected
/// with the rough pose) with the **observed** keypoint o_i. Its residual is
///
///     r_i = o_i - p_i   [px]
///
/// optionally with a third, stereo component `u_right` (ORB-SLAM2's RGB-D/stereo residual
/// `(u, v, u_right)` where `u_right = u - bf / depth`). Each match may carry the scale sigma_i of
/// its keypoint (ORB-SLAM: sigma_i = 1.2^octave, so sigma_i^2 = 1.2^(2 octave) is the variance
/// factor of its level) and a prior flag "on a dynamic mask" (from a detector or segmentation).
///
/// Optional evidence per match, unknown (NaN) unless set: the depth of the predicted point in
/// the current camera [m] (it groups neighbours in 3-D), the distance from the keypoint to the
/// nearest pixel of a dynamic-object mask [px], and the caller's persistence prior — the
/// share, with forgetting, of past frames in which this track or map point was screened out.
/// The screen stays stateless: that history is the caller's to keep and pass in.
///
/// Threading: `Matches` is a plain container; concurrent const access is safe.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "hbos/error.hpp"

namespace hbos {

template <class Scalar>
class ReprojectionScreen;

/// ORB-SLAM's scale sigma of a keypoint detected at pyramid `octave`: `scale_factor^octave`.
[[nodiscard]] inline double sigma_from_octave(int octave, double scale_factor = 1.2) {
  detail::require(octave >= 0, "octave must be >= 0, got ", octave);
  detail::require(scale_factor >= 1.0 && std::isfinite(scale_factor),
                  "scale_factor must be finite and >= 1, got ", scale_factor);
  return std::pow(scale_factor, octave);
}

/// The matches of one frame, stored column-wise so a screen reads them without copies.
/// Reuse one object across frames: `clear()` keeps the capacity, so after the largest frame has
/// been seen, filling it allocates nothing.
template <class Scalar>
class Matches {
  static_assert(std::is_floating_point_v<Scalar>, "Matches needs float or double");

 public:
  using Index = Eigen::Index;
  using Vector2 = Eigen::Matrix<Scalar, 2, 1>;

  /// Removes every match, keeping the storage.
  void clear() noexcept {
    predicted_x_.clear();
    predicted_y_.clear();
    observed_x_.clear();
    observed_y_.clear();
    predicted_right_.clear();
    observed_right_.clear();
    sigma_.clear();
    information_.clear();
    flag_.clear();
    depth_.clear();
    mask_distance_.clear();
    history_.clear();
    n_stereo_ = 0;
    n_flagged_ = 0;
  }

  /// Reserves storage for `n` matches.
  void reserve(Index n) {
    detail::require(n >= 0, "cannot reserve a negative number of matches, got ", n);
    const auto k = static_cast<std::size_t>(n);
    predicted_x_.reserve(k);
    predicted_y_.reserve(k);
    observed_x_.reserve(k);
    observed_y_.reserve(k);
    predicted_right_.reserve(k);
    observed_right_.reserve(k);
    sigma_.reserve(k);
    information_.reserve(k);
    flag_.reserve(k);
    depth_.reserve(k);
    mask_distance_.reserve(k);
    history_.reserve(k);
  }

  /// Appends a monocular match.
  /// \param predicted       [px] the reprojected point
  /// \param observed        [px] the matched keypoint
  /// \param sigma           the keypoint's scale sigma (see sigma_from_octave), finite, > 0
  /// \param on_dynamic_mask the prior: the keypoint lies on a dynamic object's mask
  void add(const Vector2& predicted, const Vector2& observed, Scalar sigma = Scalar(1),
           bool on_dynamic_mask = false) {
    const Scalar none = std::numeric_limits<Scalar>::quiet_NaN();
    push(predicted, observed, none, none, sigma, on_dynamic_mask);
  }

  /// Replaces every match with the n monocular matches of the caller's columns: match i is
  /// predicted.col(i), observed.col(i) [px], sigma(i) and on_dynamic_mask(i), as n calls of
  /// add() after clear() would make it (the same values, bit for bit), checked the same way. The
  /// checks run over every match first, then each column is written once (add() makes a call,
  /// four checks with their branches and twelve appends per match); an invalid match throws
  /// InvalidArgument naming its index and field (the first one add() would have thrown on), and
  /// leaves the matches as they were. A 2 x n column-major matrix is the layout of an array of (x,
  /// y) points.
  void assign(const Eigen::Ref<const Eigen::Matrix<Scalar, 2, Eigen::Dynamic>>& predicted,
              const Eigen::Ref<const Eigen::Matrix<Scalar, 2, Eigen::Dynamic>>& observed,
              const Eigen::Ref<const Eigen::Array<Scalar, Eigen::Dynamic, 1>>& sigma,
              const Eigen::Ref<const Eigen::Array<bool, Eigen::Dynamic, 1>>& on_dynamic_mask) {
    const Index n = predicted.cols();
    detail::require(observed.cols() == n && sigma.size() == n && on_dynamic_mask.size() == n,
                    "assign needs columns of one length: predicted ", n, ", observed ",
                    observed.cols(), ", sigma ", sigma.size(), ", on_dynamic_mask ",
                    on_dynamic_mask.size());
    // The checks of add() first, over whole columns (Eigen arrays, vectorised where the points
    // lie contiguously), so an invalid frame changes nothing; the first failing match is looked
    // for, and named, only then. sigma^2 in the normal range keeps sigma finite and nonzero.
    using Array = Eigen::Array<Scalar, Eigen::Dynamic, 1>;
    const auto finite = [](const auto& points) {
      return points.outerStride() == 2
                 ? Eigen::Map<const Array>(points.data(), 2 * points.cols()).allFinite()
                 : points.allFinite();
    };
    constexpr Scalar kMin = std::numeric_limits<Scalar>::min();
    const bool valid =
        finite(predicted) && finite(observed) &&
        (sigma > Scalar(0) && sigma * sigma >= kMin && sigma * sigma <= Scalar(1) / kMin).all();
    if (!valid) {
      for (Index i = 0; i < n; ++i) check_match(i, predicted.col(i), observed.col(i), sigma(i));
    }
    // Then each column written once, in one pass.
    const auto k = static_cast<std::size_t>(n);
    for (auto* c :
         {&predicted_x_, &predicted_y_, &observed_x_, &observed_y_, &sigma_, &information_,
          &predicted_right_, &observed_right_, &depth_, &mask_distance_, &history_})
      c->resize(k);
    flag_.resize(k);
    // Raw pointers, read once: a store through the uint8_t flags may alias anything, so the
    // vectors' data pointers would otherwise be reloaded for every match.
    Scalar* const out_px = predicted_x_.data();
    Scalar* const out_py = predicted_y_.data();
    Scalar* const out_ox = observed_x_.data();
    Scalar* const out_oy = observed_y_.data();
    std::uint8_t* const out_flag = flag_.data();
    Index flagged = 0;
    for (Index i = 0; i < n; ++i) {
      const auto j = static_cast<std::size_t>(i);
      out_px[j] = predicted(0, i);
      out_py[j] = predicted(1, i);
      out_ox[j] = observed(0, i);
      out_oy[j] = observed(1, i);
      const bool f = on_dynamic_mask(i);
      out_flag[j] = f ? 1 : 0;
      flagged += f ? 1 : 0;
    }
    // Whole columns (Eigen arrays: two divisions at a time), as push: 1 / sigma^2.
    Eigen::Map<Array>(sigma_.data(), n) = sigma;
    Eigen::Map<Array>(information_.data(), n) = Scalar(1) / (sigma * sigma);
    const Scalar unknown = std::numeric_limits<Scalar>::quiet_NaN();
    for (auto* c : {&predicted_right_, &observed_right_, &depth_, &mask_distance_, &history_})
      std::fill(c->begin(), c->end(), unknown);
    n_stereo_ = 0;
    n_flagged_ = flagged;
  }

  /// Appends a stereo / RGB-D match with the right-image coordinates (ORB-SLAM2's `u_right`,
  /// for RGB-D `u - bf / depth`) of the prediction and of the keypoint [px].
  void add_stereo(const Vector2& predicted, const Vector2& observed, Scalar predicted_u_right,
                  Scalar observed_u_right, Scalar sigma = Scalar(1), bool on_dynamic_mask = false) {
    detail::require(std::isfinite(predicted_u_right) && std::isfinite(observed_u_right), "match ",
                    size(), ": u_right is not finite (predicted ", predicted_u_right, ", observed ",
                    observed_u_right, ")");
    push(predicted, observed, predicted_u_right, observed_u_right, sigma, on_dynamic_mask);
    ++n_stereo_;
  }

  /// Replaces the prediction of match i (used when the pose is refined and points reprojected).
  void set_predicted(Index i, const Vector2& predicted, Scalar predicted_u_right = Scalar(0)) {
    check_index(i);
    detail::require(predicted.allFinite() && std::isfinite(predicted_u_right), "match ", i,
                    ": new prediction is not finite (", predicted.x(), ", ", predicted.y(), ", ",
                    predicted_u_right, ")");
    const auto k = static_cast<std::size_t>(i);
    if (has_right(i)) predicted_right_[k] = predicted_u_right;
    predicted_x_[k] = predicted.x();
    predicted_y_[k] = predicted.y();
  }

  /// Sets the depth of match i's predicted point in the current camera [m], finite and > 0.
  void set_depth(Index i, Scalar depth_m) {
    check_index(i);
    detail::require(std::isfinite(depth_m) && depth_m > Scalar(0), "match ", i,
                    ": depth must be finite and > 0 m, got ", depth_m);
    depth_[static_cast<std::size_t>(i)] = depth_m;
  }
  /// Sets the distance from match i's keypoint to the nearest dynamic-mask pixel [px], >= 0
  /// (+inf: the frame has a mask but no masked pixel; leave unset when there is no mask at all).
  void set_mask_distance(Index i, Scalar distance_px) {
    check_index(i);
    detail::require(!std::isnan(distance_px) && distance_px >= Scalar(0), "match ", i,
                    ": mask distance must be >= 0 px, got ", distance_px);
    mask_distance_[static_cast<std::size_t>(i)] = distance_px;
  }
  /// Sets the caller's persistence prior of match i, in [0, 1] (see the file comment).
  void set_outlier_history(Index i, Scalar history) {
    check_index(i);
    detail::require(history >= Scalar(0) && history <= Scalar(1), "match ", i,
                    ": outlier history must lie in [0, 1], got ", history);
    history_[static_cast<std::size_t>(i)] = history;
  }
  /// Depth [m], mask distance [px] and outlier history of match i; NaN when not set.
  [[nodiscard]] Scalar depth(Index i) const { return depth_[static_cast<std::size_t>(i)]; }
  [[nodiscard]] Scalar mask_distance(Index i) const {
    return mask_distance_[static_cast<std::size_t>(i)];
  }
  [[nodiscard]] Scalar outlier_history(Index i) const {
    return history_[static_cast<std::size_t>(i)];
  }

  [[nodiscard]] Index size() const { return static_cast<Index>(sigma_.size()); }
  [[nodiscard]] bool empty() const { return sigma_.empty(); }
  /// Number of matches added with add_stereo.
  [[nodiscard]] Index stereo_count() const { return n_stereo_; }
  /// Number of matches flagged on a dynamic mask.
  [[nodiscard]] Index flagged_count() const { return n_flagged_; }

  [[nodiscard]] Vector2 predicted(Index i) const {
    const auto k = static_cast<std::size_t>(i);
    return {predicted_x_[k], predicted_y_[k]};
  }
  [[nodiscard]] Vector2 observed(Index i) const {
    const auto k = static_cast<std::size_t>(i);
    return {observed_x_[k], observed_y_[k]};
  }
  /// r_i = observed - predicted [px].
  [[nodiscard]] Vector2 residual(Index i) const {
    const auto k = static_cast<std::size_t>(i);
    return {observed_x_[k] - predicted_x_[k], observed_y_[k] - predicted_y_[k]};
  }
  /// True when match i carries a stereo component.
  [[nodiscard]] bool has_right(Index i) const {
    return !std::isnan(observed_right_[static_cast<std::size_t>(i)]);
  }
  /// The stereo residual component u_right(observed) - u_right(predicted) [px], or 0 if none.
  [[nodiscard]] Scalar right_residual(Index i) const {
    const auto k = static_cast<std::size_t>(i);
    return has_right(i) ? observed_right_[k] - predicted_right_[k] : Scalar(0);
  }
  [[nodiscard]] Scalar sigma(Index i) const { return sigma_[static_cast<std::size_t>(i)]; }
  /// The information 1 / sigma_i^2 of match i (ORB-SLAM2's invSigma2 of its level).
  [[nodiscard]] Scalar information(Index i) const {
    return information_[static_cast<std::size_t>(i)];
  }
  [[nodiscard]] bool on_dynamic_mask(Index i) const {
    return flag_[static_cast<std::size_t>(i)] != 0;
  }

  /// Squared residual norm over all components (2, or 3 for stereo) [px^2].
  [[nodiscard]] Scalar squared_residual(Index i) const {
    const Vector2 r = residual(i);
    const Scalar right = right_residual(i);
    return r.squaredNorm() + right * right;
  }

 private:
  // The screen reads the columns directly, as whole arrays (vectorised arithmetic).
  friend class ReprojectionScreen<Scalar>;

  /// Throws InvalidArgument naming match i and its field unless the match is valid.
  static void check_match(Index i, const Vector2& predicted, const Vector2& observed,
                          Scalar sigma) {
    detail::require(predicted.allFinite(), "match ", i, ": predicted pixel is not finite (",
                    predicted.x(), ", ", predicted.y(), ")");
    detail::require(observed.allFinite(), "match ", i, ": observed pixel is not finite (",
                    observed.x(), ", ", observed.y(), ")");
    detail::require(std::isfinite(sigma) && sigma > Scalar(0), "match ", i,
                    ": sigma must be finite and > 0, got ", sigma);
    // Screens use both sigma^2 and the information 1/sigma^2; a sigma whose square over- or
    // underflows would turn them into inf * 0 = NaN.
    // (1/s2 is normal exactly when s2 <= 1/min, a power of two: no division per match)
    const Scalar s2 = sigma * sigma;
    constexpr Scalar kMin = std::numeric_limits<Scalar>::min();
    if (!(s2 >= kMin && s2 <= Scalar(1) / kMin))  // (the message's bounds cost square roots)
      detail::require(false, "match ", i, ": sigma ", sigma,
                      " is out of range: sigma^2 and 1/sigma^2 must be finite and normal, so ",
                      "sigma lies in [", std::sqrt(kMin), ", ", Scalar(1) / std::sqrt(kMin), "]");
  }

  void push(const Vector2& predicted, const Vector2& observed, Scalar predicted_right,
            Scalar observed_right, Scalar sigma, bool flag) {
    // One test on the common path; the checks that name the field only for an invalid match.
    // (sigma^2 in the normal range keeps sigma finite and nonzero.)
    const Scalar s2 = sigma * sigma;
    constexpr Scalar kMin = std::numeric_limits<Scalar>::min();
    if (!(predicted.allFinite() && observed.allFinite() && sigma > Scalar(0) && s2 >= kMin &&
          s2 <= Scalar(1) / kMin))
      check_match(size(), predicted, observed, sigma);
    predicted_x_.push_back(predicted.x());
    predicted_y_.push_back(predicted.y());
    observed_x_.push_back(observed.x());
    observed_y_.push_back(observed.y());
    predicted_right_.push_back(predicted_right);
    observed_right_.push_back(observed_right);
    sigma_.push_back(sigma);
    // Kept per match, as ORB-SLAM2 keeps invSigma2 per level: the gates then multiply instead of
    // dividing, once per screening round.
    information_.push_back(Scalar(1) / s2);
    flag_.push_back(flag ? 1 : 0);
    n_flagged_ += flag ? 1 : 0;
    const Scalar unknown = std::numeric_limits<Scalar>::quiet_NaN();
    depth_.push_back(unknown);
    mask_distance_.push_back(unknown);
    history_.push_back(unknown);
  }
  void check_index(Index i) const {
    detail::require(i >= 0 && i < size(), "match index ", i, " out of range [0, ", size(), ")");
  }

  std::vector<Scalar> predicted_x_, predicted_y_, observed_x_, observed_y_;
  std::vector<Scalar> predicted_right_, observed_right_;  // NaN for monocular matches
  std::vector<Scalar> sigma_;
  std::vector<Scalar> information_;  // 1 / sigma^2
  std::vector<std::uint8_t> flag_;
  std::vector<Scalar> depth_, mask_distance_, history_;  // NaN = not set
  Index n_stereo_ = 0;
  Index n_flagged_ = 0;
};

using Matchesd = Matches<double>;
using Matchesf = Matches<float>;

}  // namespace hbos
