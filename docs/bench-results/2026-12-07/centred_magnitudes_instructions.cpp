// Stop 45: what the centred magnitudes cost before and after they went over whole columns, in
// instructions, and that every output keeps its bits. The default screen on bench_screening's
// 1000-match frame (BM_hbos_default's: seed 42, 5 % leaked dynamic matches, 3 % gross, a rough
// pose 1.5 px off), 100 screens, in double or float (argument "float"); prints a hash of every
// score's, magnitude's and coherence's bits and every decision, so two builds can be checked
// for the same outputs.
//
//   g++ -std=c++17 -O2 -g -DNDEBUG -I<headers>/include -I<repo> -I/usr/include/eigen3 \
//       centred_magnitudes_instructions.cpp -o instr
//   valgrind --tool=callgrind \
//     --toggle-collect='hbos::ReprojectionScreen<double>::run_gated*' ./instr
//
// Built against the headers of d693f92 (before) and of d693f92 with
// centred_magnitudes_columns.patch applied (after); results in centred_magnitudes_instructions.txt.
#include <cstdio>
#include <cstring>
#include <hbos/screening.hpp>
#include "tests/support/synthetic_scene.hpp"

template <class Scalar>
void run(const hbos_test::Scene& scene, const char* label) {
  hbos::Matches<Scalar> m;
  for (Eigen::Index i = 0; i < scene.size(); ++i)
    m.add(scene.predicted.col(i).template cast<Scalar>().eval(),
          scene.observed.col(i).template cast<Scalar>().eval(), static_cast<Scalar>(scene.sigma(i)),
          scene.on_dynamic_mask(i));
  hbos::ReprojectionScreen<Scalar> screen{hbos::HbosScreen{}};
  screen.reserve(1000);
  double kept = 0;
  unsigned long long hash = 1469598103934665603ULL;
  for (int k = 0; k < 100; ++k) {
    const auto& r = screen.screen(m);
    for (Eigen::Index i = 0; i < r.size(); ++i) {
      for (const Scalar v : {r.scores()(i), r.magnitude(i), r.coherence(i)}) {
        unsigned long long b = 0;
        std::memcpy(&b, &v, sizeof(Scalar));
        hash = (hash ^ b) * 1099511628211ULL;
      }
      hash = (hash ^ static_cast<unsigned long long>(r.inlier(i))) * 1099511628211ULL;
    }
    kept += static_cast<double>(r.n_inliers());
  }
  std::printf("%s kept %.0f hash %016llx\n", label, kept, hash);
}

int main(int argc, char** argv) {
  hbos_test::SceneConfig c;
  c.seed = 42;
  c.n_matches = 1000;
  c.person_share = 0.035;
  c.edge_share = 0.0075;
  c.carried_share = 0.0075;
  c.gross_share = 0.03;
  c.pose_error_px = 1.5;
  const auto scene = hbos_test::make_scene(c);
  if (argc > 1 && std::strcmp(argv[1], "float") == 0) {
    run<float>(scene, "float");
  } else {
    run<double>(scene, "double");
  }
}
