#pragma once
/// \file
/// Stage 2: frame-to-frame matching of the current frame's ORB descriptors against the previous
/// frame's features that have depth (and so a 3D point).

#include "frontend/config.hpp"
#include "frontend/orb_extraction.hpp"

#include <vector>

namespace hbos::slam {

struct FeatureMatch {
  int previous = 0;  ///< index into the previous frame's Features
  int current = 0;   ///< index into the current frame's Features
  int hamming = 0;   ///< descriptor distance [bits]
};

class FrameMatcher {
 public:
  /// Throws hbos::InvalidArgument on settings out of range.
  explicit FrameMatcher(const MatchingConfig& config);

  /// Brute-force Hamming matching: for each current feature the nearest previous one with depth,
  /// kept when within max_hamming, passing the ratio test (if on) and, with cross_check, when the
  /// current feature is also the previous one's nearest. Sorted by current index.
  [[nodiscard]] std::vector<FeatureMatch> match(const Features& previous,
                                                const Features& current) const;

 private:
  MatchingConfig config_;
};

}  // namespace hbos::slam
