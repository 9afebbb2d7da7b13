// Scratch: where does the default screen's static loss come from on the labelled cases (RANSAC)?
#include <cstdio>
#include <hbos/screening.hpp>
#include "screening_cases.hpp"
using namespace hbos_test;
int main(int argc, char** argv) {
  for (int a = 1; a < argc; ++a) {
    for (const std::string& folder : list_case_folders(argv[a])) {
      for (CasePose pose : {CasePose::Ransac, CasePose::PerturbedGt}) {
        ScreeningCase c = load_screening_case(folder, pose);
        hbos::ReprojectionScreend def;
        hbos::ScreenConfig cc;
        cc.strategy = hbos::ChiSquareGate{};
        hbos::ReprojectionScreend chi(cc);
        long st = 0, d_def = 0, d_chi = 0, by_gate = 0, by_coh = 0, by_mask = 0, by_hist = 0,
             both = 0, onmask_drop = 0, dyn = 0, dyn_def = 0, dyn_chi = 0, dyn_gate = 0, dyn_ev = 0;
        for (CasePair& p : c.pairs) {
          const auto& r = def.screen(p.matches);
          std::vector<std::uint8_t> in_def(r.inliers().data(), r.inliers().data() + r.size());
          const double gate = r.magnitude_cut();
          std::vector<double> mag(r.size());
          for (Eigen::Index i = 0; i < r.size(); ++i) mag[i] = r.magnitude(i);
          auto C = r.contributions();
          const auto& q = chi.screen(p.matches);
          for (Eigen::Index i = 0; i < p.size(); ++i) {
            if (p.gross[i]) continue;
            const bool kd = in_def[i], kc = q.inlier(i);
            if (p.dynamic[i]) {
              ++dyn;
              dyn_def += kd;
              dyn_chi += kc;
              if (!kd) {
                if (mag[i] > gate)
                  ++dyn_gate;
                else
                  ++dyn_ev;
              }
              continue;
            }
            ++st;
            if (!kd) {
              ++d_def;
              if (p.on_mask[i]) ++onmask_drop;
              if (mag[i] > gate)
                ++by_gate;
              else {
                if (C(i, 1) > 1.5) ++by_coh;
                if (C(i, 2) > 1.5) ++by_mask;
                if (C(i, 3) > 1.5) ++by_hist;
              }
            }
            if (!kc) ++d_chi;
            if (!kd && !kc) ++both;
          }
        }
        std::printf(
            "%-28s %-5s static %6ld lost def %.2f%% chi %.2f%% | def: gate %ld coh %ld mask %ld "
            "hist %ld onmask %ld both %ld | dyn %ld kept def %.1f chi %.1f  def-drop gate %ld ev "
            "%ld\n",
            c.name.c_str(), pose == CasePose::Ransac ? "ransac" : "pgt", st, 100.0 * d_def / st,
            100.0 * d_chi / st, by_gate, by_coh, by_mask, by_hist, onmask_drop, both, dyn,
            dyn ? 100.0 * dyn_def / dyn : 0., dyn ? 100.0 * dyn_chi / dyn : 0., dyn_gate, dyn_ev);
      }
    }
  }
}
