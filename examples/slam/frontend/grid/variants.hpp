#pragma once
/// \file
/// The semi-real sequences of the variant grid (`hbos-slam --variant-grid`): the person
/// composited into the real frames along several paths, fixed by a rule written down before any
/// result was looked at, so that the spread over them is the run-to-run spread of a ranking.
///
/// The rule (one cut-out exists, examples/slam/data/person/): 2 depths x 2 directions x 2 paths
/// = 8 variants.
///   - median depth 0.7 m (the demo's) and 1.2 m;
///   - image motion +5.5 px/frame (rightwards, the demo's) and -5.5 px/frame (leftwards);
///   - path: the cut-out's left edge starts 40 px from the image edge it leaves from (the demo's
///     40 px) or 200 px from it, i.e. start 40 / 200 px moving right, and
///     width - cut-out width - 40 / 200 px moving left, so every path stays in view for 37 frames.
/// Nothing else changes (same frames, camera, masks, screens, rough pose, rounds).

#include "frontend/config.hpp"

#include <string>
#include <vector>

namespace hbos::slam {

/// One semi-real sequence: where and how the person moves.
struct PersonVariant {
  std::string name;  ///< e.g. `d0.7 v+5.5 x40`
  double depth_m = 0.7;
  double speed_px_per_frame = 5.5;
  double start_x_px = 40.0;
};

/// The 8 variants of the rule above for frames `image_width` px wide and a cut-out
/// `cutout_width` px wide, the demo's own path (0.7 m, +5.5 px/frame, 40 px) first.
[[nodiscard]] std::vector<PersonVariant> semireal_variants(int image_width, int cutout_width);

/// `scenario` with the person on `variant`'s path (add_person set).
[[nodiscard]] ScenarioConfig with_variant(ScenarioConfig scenario, const PersonVariant& variant);

}  // namespace hbos::slam
