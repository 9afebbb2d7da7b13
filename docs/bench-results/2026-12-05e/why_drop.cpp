// Throwaway: why does the default drop the statics chi2 keeps?
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <hbos/screening.hpp>
#include <nlohmann/json.hpp>
#include "screening_cases.hpp"
using namespace hbos_test;
int main(int argc, char** argv) {
  std::string root = argv[1];
  nlohmann::json cj = nlohmann::json::parse(std::ifstream(root + "/cases.json"));
  for (const auto& name : std::vector<std::string>{
           "static", "b_walk_exact", "b_slow_none", "b_toward_degraded", "a_slow_degraded",
           "ab_mixed_none", "a_slow_none", "h_static_reverse", "h_b_slow_none",
           "h_a_toward_degraded", "h_ab_slow_none"}) {
    if (!std::filesystem::exists(root + "/" + name)) continue;
    ScreeningCase c = load_screening_case(root + "/" + name, CasePose::Ransac);
    hbos::ReprojectionScreend def{hbos::ScreenConfig{}},
        chi{hbos::ScreenConfig{hbos::ChiSquareGate{}}};
    long st = 0, d_def = 0, d_chi = 0, both = 0, def_only_ev = 0, def_only_gate = 0, chi_only = 0;
    long def_only_raw_in_gate_centred_out = 0, nearmask = 0;
    for (const CasePair& p : c.pairs) {
      if (p.size() == 0) continue;
      std::vector<uint8_t> keep_chi(p.size());
      {
        const auto& r = chi.screen(p.matches);
        for (Eigen::Index i = 0; i < p.size(); ++i) keep_chi[i] = r.inlier(i);
      }
      const auto& r = def.screen(p.matches);
      const double G = r.magnitude_cut();
      for (Eigen::Index i = 0; i < p.size(); ++i) {
        if (p.dynamic[i] || p.gross[i]) continue;
        ++st;
        bool kd = r.inlier(i), kc = keep_chi[i];
        d_def += !kd;
        d_chi += !kc;
        if (!kd && !kc) ++both;
        if (!kd && kc) {
          if (r.magnitude(i) > G) {
            ++def_only_gate;
          } else {
            ++def_only_ev;
          }
          if (p.mask_distance_px[i] >= 0 && p.mask_distance_px[i] < 10) ++nearmask;
        }
        if (kd && !kc) ++chi_only;
      }
    }
    std::printf(
        "%-22s statics %6ld  def %5.2f%%  chi2 %5.2f%%  both %4ld  def-only: gate %4ld evidence "
        "%4ld (near mask %ld)  chi2-only %4ld\n",
        name.c_str(), st, 100.0 * d_def / st, 100.0 * d_chi / st, both, def_only_gate, def_only_ev,
        nearmask, chi_only);
  }
}
