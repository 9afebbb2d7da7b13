// Scratch: default screen's gate floor / scales / coherence floor swept; per case static loss and
// dynamics kept against chi2 (single round).
#include <cstdio>
#include <hbos/screening.hpp>
#include "screening_cases.hpp"
using namespace hbos_test;
struct R {
  long st = 0, sl = 0, dyn = 0, dk = 0;
};
R run(const ScreeningCase& c, const hbos::ScreenConfig& cfg) {
  hbos::ReprojectionScreend s(cfg);
  R r;
  for (const CasePair& p : c.pairs) {
    const auto& q = s.screen(p.matches);
    for (Eigen::Index i = 0; i < p.size(); ++i) {
      if (p.gross[i]) continue;
      if (p.dynamic[i]) {
        ++r.dyn;
        r.dk += q.inlier(i);
      } else {
        ++r.st;
        r.sl += !q.inlier(i);
      }
    }
  }
  return r;
}
int main(int argc, char** argv) {
  std::vector<std::pair<double, double>> settings;  // gate floor, coherence floor
  for (double f : {2.447, 2.55, 2.65, 2.75})
    for (double cf : {2.0, 2.5, 3.0}) settings.push_back({f, cf});
  std::vector<int> pass(settings.size(), 0), cases(settings.size(), 0),
      passstat(settings.size(), 0);
  for (int a = 1; a < argc; ++a)
    for (const std::string& folder : list_case_folders(argv[a]))
      for (CasePose pose : {CasePose::Ransac, CasePose::PerturbedGt}) {
        ScreeningCase c = load_screening_case(folder, pose);
        hbos::ScreenConfig cc;
        cc.strategy = hbos::ChiSquareGate{};
        const R chi = run(c, cc);
        std::printf("%-22s %-6s chi2 %5.2f/%5.1f |", c.name.c_str(),
                    pose == CasePose::Ransac ? "ransac" : "pgt", 100.0 * chi.sl / chi.st,
                    chi.dyn ? 100.0 * chi.dk / chi.dyn : 0.);
        for (std::size_t k = 0; k < settings.size(); ++k) {
          hbos::HbosScreen h;
          h.gate.floor = settings[k].first;
          h.coherence.floor = settings[k].second;
          hbos::ScreenConfig cfg;
          cfg.strategy = h;
          const R d = run(c, cfg);
          const bool ok_static = d.sl * chi.st <= chi.sl * d.st;
          const bool ok = ok_static && (chi.dyn == 0 || d.dk * chi.dyn < chi.dk * d.dyn);
          pass[k] += ok;
          passstat[k] += ok_static;
          ++cases[k];
          std::printf(" %5.2f/%5.1f%s", 100.0 * d.sl / d.st, d.dyn ? 100.0 * d.dk / d.dyn : 0.,
                      ok ? "*" : " ");
        }
        std::printf("\n");
      }
  for (std::size_t k = 0; k < settings.size(); ++k)
    std::printf("floor %.3f coh %.1f: beats chi2 (static<=, dyn<) in %d of %d, static<= in %d\n",
                settings[k].first, settings[k].second, pass[k], cases[k], passstat[k]);
}
