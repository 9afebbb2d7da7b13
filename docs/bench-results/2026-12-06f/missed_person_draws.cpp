// Which person the renderer's person_missed variant leaves unmasked, per seed, with two people
// and with three: MaskPlan::make's first draw of the seed's kMaskPersonMissed stream, taken
// modulo the number of people (examples/render/render/masks.cpp). The stream does not depend on
// the scenario, so one seed misses the same person in every scenario.
// Build: g++ -std=c++17 -I examples/render missed_person_draws.cpp -o missed_person_draws
#include "render/random.hpp"

#include <cstdio>

int main() {
  using hbos::render::Stream;
  int of_three[3] = {0, 0, 0};
  for (unsigned long long seed = 1; seed <= 300; ++seed) {
    hbos::render::Rng r = hbos::render::stream(seed, Stream::kMaskPersonMissed);
    const unsigned long long x = r.next();
    if (seed <= 20) {
      std::printf("seed %llu: two people -> person %llu, three people -> person %llu\n", seed,
                  1 + x % 2, 1 + x % 3);
    }
    ++of_three[x % 3];
  }
  std::printf("seeds 1-300 with three people: person 1 %d, person 2 %d, person 3 %d times\n",
              of_three[0], of_three[1], of_three[2]);
}
