// The default screen on the labelled cases whose matches carry a mask flag, with and without
// CoherenceEvidence::flagged_consensus: statics dropped and dynamics kept, split by the flag
// (on_mask: within 15 px of the degraded mask). Single round per pair, gross mismatches left out.
// Build by hand from the repository's root:
//   g++ -O2 -std=c++17 -Iinclude -Itests/support -I/usr/include/eigen3 \
//     docs/bench-results/2026-12-05g/flagged_consensus_cases.cpp -o /tmp/flagged_consensus_cases
//   /tmp/flagged_consensus_cases tests/data/screening_cases/a_slow_degraded ...
#include <cstdio>

#include "hbos/screening.hpp"
#include "screening_cases.hpp"

int main(int argc, char** argv) {
  for (int a = 1; a < argc; ++a) {
    for (const auto pose : {hbos_test::CasePose::Ransac, hbos_test::CasePose::PerturbedGt}) {
      const hbos_test::ScreeningCase c = hbos_test::load_screening_case(argv[a], pose, true);
      for (const bool consensus : {false, true}) {
        hbos::HbosScreen s;
        s.coherence.flagged_consensus = consensus;
        hbos::ReprojectionScreend screen(s);
        long statics[2] = {0, 0}, dropped[2] = {0, 0}, dynamics[2] = {0, 0}, kept[2] = {0, 0};
        for (const hbos_test::CasePair& p : c.pairs) {
          const auto& r = screen.screen(p.matches);
          for (Eigen::Index i = 0; i < p.size(); ++i) {
            const auto k = static_cast<std::size_t>(i);
            const int f = p.on_mask[k] != 0 ? 1 : 0;
            if (p.gross[k] != 0) continue;
            if (p.dynamic[k] != 0) {
              ++dynamics[f];
              kept[f] += r.inlier(i) ? 1 : 0;
            } else {
              ++statics[f];
              dropped[f] += r.inlier(i) ? 0 : 1;
            }
          }
        }
        const auto pct = [](long x, long n) { return n > 0 ? 100.0 * x / n : 0.0; };
        std::printf(
            "| %s | %s | %s | %ld / %ld (%.1f %%) | %ld / %ld (%.1f %%) | %ld / %ld (%.1f %%) | "
            "%ld / %ld (%.1f %%) | %.1f / %.1f |\n",
            c.name.c_str(), pose == hbos_test::CasePose::Ransac ? "ransac" : "pgt",
            consensus ? "on" : "off", dropped[0], statics[0], pct(dropped[0], statics[0]),
            dropped[1], statics[1], pct(dropped[1], statics[1]), kept[0], dynamics[0],
            pct(kept[0], dynamics[0]), kept[1], dynamics[1], pct(kept[1], dynamics[1]),
            pct(dropped[0] + dropped[1], statics[0] + statics[1]),
            pct(kept[0] + kept[1], dynamics[0] + dynamics[1]));
      }
    }
  }
}
