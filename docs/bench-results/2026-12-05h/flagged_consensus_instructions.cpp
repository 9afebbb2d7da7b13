// Stop 36: what the flagged matches' second consensus pass costs, in instructions. The default
// screen on bench_screening's 1000-match frame with a quarter of the matches flagged (as
// BM_hbos_probation), 100 screens, with the option off or on (argument "on"); prints a hash of
// every score's and coherence's bits and decision, so two builds can be checked for the same
// outputs.
//
//   g++ -std=c++17 -O2 -g -DNDEBUG -I<headers>/include -I<repo> -I/usr/include/eigen3 \
//       flagged_consensus_instructions.cpp -o instr
//   valgrind --tool=callgrind ./instr on     # ReprojectionScreen::run_gated, inclusive
//
// Built against the headers of 7fe021b^ and of 7fe021b; results in
// flagged_consensus_instructions.txt.
#include <cstdio>
#include <cstring>
#include <hbos/screening.hpp>
#include "tests/support/synthetic_scene.hpp"
int main(int argc, char** argv) {
  const bool consensus = argc > 1 && std::strcmp(argv[1], "on") == 0;
  hbos_test::SceneConfig c;
  c.seed = 42;
  c.n_matches = 1000;
  c.person_share = 0.035;
  c.edge_share = 0.0075;
  c.carried_share = 0.0075;
  c.gross_share = 0.03;
  c.pose_error_px = 1.5;
  const auto scene = hbos_test::make_scene(c);
  hbos::Matchesd m;
  for (Eigen::Index i = 0; i < scene.size(); ++i)
    m.add(scene.predicted.col(i), scene.observed.col(i), scene.sigma(i),
          scene.on_dynamic_mask(i) || i % 4 == 0);
  hbos::HbosScreen h;
  h.coherence.flagged_consensus = consensus;
  hbos::ReprojectionScreend screen(h);
  screen.reserve(1000);
  double sum = 0;
  unsigned long long hash = 1469598103934665603ULL;
  for (int k = 0; k < 100; ++k) {
    const auto& r = screen.screen(m);
    for (Eigen::Index i = 0; i < r.size(); ++i) {
      for (const double v : {r.scores()(i), r.coherence(i)}) {
        unsigned long long b;
        std::memcpy(&b, &v, 8);
        hash = (hash ^ b) * 1099511628211ULL;
      }
      hash = (hash ^ (unsigned long long)r.inlier(i)) * 1099511628211ULL;
    }
    sum += r.n_inliers();
  }
  std::printf("%s kept %.0f hash %016llx\n", consensus ? "on" : "off", sum, hash);
}
