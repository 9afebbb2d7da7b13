#include "frontend/grid/variants.hpp"

#include <fmt/format.h>

namespace hbos::slam {

std::vector<PersonVariant> semireal_variants(int image_width, int cutout_width) {
  std::vector<PersonVariant> variants;
  for (const double depth : {0.7, 1.2}) {
    for (const double speed : {5.5, -5.5}) {
      for (const int margin : {40, 200}) {
        PersonVariant v;
        v.depth_m = depth;
        v.speed_px_per_frame = speed;
        v.start_x_px = speed > 0 ? margin : image_width - cutout_width - margin;
        v.name = fmt::format("d{:.1f} v{:+.1f} x{:.0f}", depth, speed, v.start_x_px);
        variants.push_back(v);
      }
    }
  }
  return variants;
}

ScenarioConfig with_variant(ScenarioConfig scenario, const PersonVariant& variant) {
  scenario.add_person = true;
  scenario.depth_m = variant.depth_m;
  scenario.speed_px_per_frame = variant.speed_px_per_frame;
  scenario.start_x_px = variant.start_x_px;
  return scenario;
}

}  // namespace hbos::slam
