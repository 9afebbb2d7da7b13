// The default screen's outputs hashed on every real case pair and 240 synthetic frames: build it at
// two commits and diff the outputs to show a change keeps every bit (docs/benchmarks.md, "The
// default screen, faster bit for bit"). Not part of the build. From the repository's root:
//
//   g++ -std=c++17 -O2 -DNDEBUG -Iinclude -Itests/support -I/usr/include/eigen3 $THIS -o identity
//
//   ./identity tests/data/screening_cases tests/data/screening_cases_holdout > hashes.txt

#include <cstdio>
#include <cstring>
#include <hbos/screening.hpp>
#include "screening_cases.hpp"
#include "screening_eval.hpp"
#include "synthetic_scene.hpp"

static unsigned long long h = 1469598103934665603ull;
template <class T>
void mix(const T& v) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  for (unsigned char c : b) {
    h ^= c;
    h *= 1099511628211ull;
  }
}
template <class S>
void dump(const char* tag, int k, const hbos::ScreenResult<S>& r) {
  h = 1469598103934665603ull;
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    mix(r.score(i));
    mix(r.inlier(i));
    mix(r.magnitude(i));
    mix(r.coherence(i));
  }
  mix(r.threshold());
  mix(r.noise_scale());
  mix(r.magnitude_cut());
  mix(r.n_rejected_by_evidence());
  const auto c = r.contributions();
  for (Eigen::Index j = 0; j < c.size(); ++j) mix(c.data()[j]);
  std::printf("%s %d %016llx %ld\n", tag, k, h, (long)r.n_inliers());
}
int main(int argc, char** argv) {
  for (int a = 1; a < argc; ++a)
    for (const auto& folder : hbos_test::list_case_folders(argv[a]))
      for (auto pose : {hbos_test::CasePose::Ransac, hbos_test::CasePose::PerturbedGt}) {
        auto c = hbos_test::load_screening_case(folder, pose);
        hbos::ReprojectionScreend screen;
        int k = 0;
        for (auto& p : c.pairs) {
          // with a history column from the track id parity, so that evidence path runs too
          dump(folder.c_str(), k, screen.screen(p.matches));
          for (Eigen::Index i = 0; i < p.matches.size(); ++i)
            p.matches.set_outlier_history(i, p.track_id[(std::size_t)i] % 5 == 0 ? 0.8 : 0.1);
          dump("history", k, screen.screen(p.matches));
          hbos::Matchesf mf;
          for (Eigen::Index i = 0; i < p.matches.size(); ++i) {
            mf.add(p.matches.predicted(i).cast<float>(), p.matches.observed(i).cast<float>(),
                   (float)p.matches.sigma(i), p.matches.on_dynamic_mask(i));
          }
          hbos::ReprojectionScreenf sf;
          dump("float", k, sf.screen(mf));
          ++k;
        }
      }
  for (std::uint64_t seed = 1; seed <= 40; ++seed)
    for (auto sc :
         {hbos_test::Scenario::Static, hbos_test::Scenario::Person, hbos_test::Scenario::Mixed}) {
      hbos_test::Conditions cond;
      cond.n_matches = seed % 3 == 0 ? 200 : 1000;
      auto cfg = hbos_test::scenario_config(sc, 0.1, seed, cond);
      auto scene = hbos_test::make_scene(cfg);
      hbos::Matchesd m;
      for (Eigen::Index i = 0; i < scene.size(); ++i)
        m.add(scene.predicted.col(i), scene.observed.col(i), scene.sigma(i),
              scene.on_dynamic_mask(i));
      hbos::ReprojectionScreend screen;
      dump("synthetic", (int)seed, screen.screen(m));
      hbos::ScreenConfig nc;
      hbos::HbosScreen hs;
      hs.residuals.center = hbos::ResidualCenter::None;
      nc.strategy = hs;
      hbos::ReprojectionScreend s2(nc);
      dump("nocenter", (int)seed, s2.screen(m));
    }
}
