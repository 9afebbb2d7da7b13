// Throwaway: pooled static loss / dynamic kept of default variants on the labelled cases.
#include <cstdio>
#include <filesystem>
#include <hbos/screening.hpp>
#include "equal_loss.hpp"
using namespace hbos_test;
struct Cfg {
  const char* name;
  bool tau;
  double z0, floor;
};
int main(int argc, char** argv) {
  std::vector<std::string> roots(argv + 1, argv + argc);
  std::vector<Cfg> cfgs = {
      {"old", false, 3, 2},         {"tau z0=2.0", true, 2.0, 2},  {"tau z0=2.2", true, 2.2, 2},
      {"tau z0=2.4", true, 2.4, 2}, {"tau z0=2.6", true, 2.6, 2},  {"tau z0=2.8", true, 2.8, 2},
      {"tau z0=3.0", true, 3.0, 2}, {"old z0=2.8", false, 2.8, 2}, {"old z0=3.2", false, 3.2, 2}};
  for (CasePose pose : {CasePose::Ransac, CasePose::PerturbedGt}) {
    std::vector<ScreeningCase> cases;
    for (auto& root : roots)
      for (auto& e : std::filesystem::directory_iterator(root))
        if (e.is_directory()) cases.push_back(load_screening_case(e.path().string(), pose));
    std::printf("pose %s\n", pose == CasePose::Ransac ? "ransac" : "pgt");
    for (const Cfg& cfg : cfgs) {
      hbos::HbosScreen h;
      h.coherence.shared_offset = cfg.tau;
      h.coherence.z0 = cfg.z0;
      h.coherence.floor = cfg.floor;
      hbos::ReprojectionScreend scr{hbos::ScreenConfig{h}};
      double sl_sum = 0, dk_sum = 0;
      int ns = 0, nd = 0;
      std::string per;
      for (const auto& c : cases) {
        CaseTally t = tally_case(c, scr);
        double sl = 100.0 * t.static_dropped / t.statics;
        sl_sum += sl;
        ++ns;
        char b[64];
        if (t.dynamics > 0) {
          double dk = 100.0 * t.dynamic_kept / t.dynamics;
          dk_sum += dk;
          ++nd;
          std::snprintf(b, 64, " %.1f/%.1f", sl, dk);
        } else
          std::snprintf(b, 64, " %.2f/-", sl);
        per += b;
      }
      std::printf("  %-14s mean static loss %.3f  mean dyn kept %.2f |%s\n", cfg.name, sl_sum / ns,
                  dk_sum / nd, per.c_str());
    }
  }
}
