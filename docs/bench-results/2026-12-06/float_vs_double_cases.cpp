// Scratch kept in docs: the default screen in float against double on the labelled cases
// (single round): how many decisions differ, and each case's static loss and dynamics kept.
#include <cstdio>
#include <hbos/screening.hpp>
#include "screening_cases.hpp"
using namespace hbos_test;
int main(int argc, char** argv) {
  long total = 0, differ = 0;
  for (int a = 1; a < argc; ++a)
    for (const std::string& folder : list_case_folders(argv[a]))
      for (CasePose pose : {CasePose::Ransac, CasePose::PerturbedGt}) {
        const ScreeningCase c = load_screening_case(folder, pose);
        hbos::ReprojectionScreend sd;
        hbos::ReprojectionScreen<float> sf;
        long st = 0, dyn = 0, sl_d = 0, sl_f = 0, dk_d = 0, dk_f = 0, n = 0, diff = 0;
        for (const CasePair& p : c.pairs) {
          hbos::Matches<float> mf;
          for (Eigen::Index i = 0; i < p.size(); ++i) {
            const auto& m = p.matches;
            mf.add(m.predicted(i).cast<float>(), m.observed(i).cast<float>(),
                   static_cast<float>(m.sigma(i)), m.on_dynamic_mask(i));
            if (!std::isnan(m.depth(i)))
              mf.set_depth(mf.size() - 1, static_cast<float>(m.depth(i)));
            if (!std::isnan(m.mask_distance(i)))
              mf.set_mask_distance(mf.size() - 1, static_cast<float>(m.mask_distance(i)));
          }
          const auto& rd = sd.screen(p.matches);
          std::vector<std::uint8_t> kd(rd.inliers().data(), rd.inliers().data() + rd.size());
          const auto& rf = sf.screen(mf);
          for (Eigen::Index i = 0; i < p.size(); ++i) {
            ++n;
            diff += kd[i] != rf.inlier(i);
            if (p.gross[i]) continue;
            if (p.dynamic[i]) {
              ++dyn;
              dk_d += kd[i];
              dk_f += rf.inlier(i);
            } else {
              ++st;
              sl_d += !kd[i];
              sl_f += !rf.inlier(i);
            }
          }
        }
        total += n;
        differ += diff;
        std::printf(
            "%-22s %-6s decisions differ %4ld of %6ld | static lost %.2f -> %.2f %% | dynamics "
            "kept %.1f -> %.1f %%\n",
            c.name.c_str(), pose == CasePose::Ransac ? "ransac" : "pgt", diff, n, 100.0 * sl_d / st,
            100.0 * sl_f / st, dyn ? 100.0 * dk_d / dyn : 0.0, dyn ? 100.0 * dk_f / dyn : 0.0);
      }
  std::printf("all: %ld of %ld decisions differ (%.3f %%)\n", differ, total,
              100.0 * differ / total);
}
