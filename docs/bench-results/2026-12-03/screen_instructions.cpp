// Instructions of the default (or paper) screen per 1000-match frame, for callgrind: run with 0
// and with 100 screens, take the difference over 100 (docs/benchmarks.md, "The default screen,
// faster bit for bit"). Not part of the build. From the repository's root:
//
//   g++ -std=c++17 -O3 -DNDEBUG -Iinclude -Itests/support -I/usr/include/eigen3 $THIS -o drive
//
//   valgrind --tool=callgrind --callgrind-out-file=/dev/null ./drive default 100

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <hbos/screening.hpp>
#include "synthetic_scene.hpp"
int main(int argc, char** argv) {
  if (argc < 3) return 2;
  hbos_test::SceneConfig c;
  c.seed = 42;
  c.n_matches = 1000;
  c.person_share = 0.035;
  c.edge_share = 0.0075;
  c.carried_share = 0.0075;
  c.gross_share = 0.03;
  c.pose_error_px = 1.5;
  auto scene = hbos_test::make_scene(c);
  hbos::Matchesd m;
  for (Eigen::Index i = 0; i < scene.size(); ++i)
    m.add(scene.predicted.col(i), scene.observed.col(i), scene.sigma(i), scene.on_dynamic_mask(i));
  hbos::ScreenStrategy st = std::strcmp(argv[1], "paper") == 0
                                ? hbos::ScreenStrategy(hbos::HbosScreen::paper())
                                : hbos::ScreenStrategy(hbos::HbosScreen{});
  hbos::ReprojectionScreend s(st);
  s.reserve(1000);
  long k = 0;
  const int reps = std::atoi(argv[2]);
  for (int i = 0; i < reps; ++i) k += s.screen(m).n_inliers();
  std::printf("%ld\n", k);
}
