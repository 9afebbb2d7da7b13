// Checks that tests/unit/test_screen_real_cases.cpp ("the statics only the default's evidence
// rejects move with the person") can fail: the same pooled ratios for an HBOS screen whose
// coherence fires at random (floor 0, z0 0). Build from the repository root:
//   g++ -O2 -std=c++17 -Iinclude -Itests -I/usr/include/eigen3 THIS.cpp -o can_fail && ./can_fail
//   DIR
#include <cstdio>
#include "support/static_disagreement.hpp"
int main(int argc, char** argv) {
  hbos::HbosScreen h;
  h.coherence.floor = 0.0;
  h.coherence.z0 = 0.0;
  hbos::ScreenConfig noisy{h};
  for (auto pose : {hbos_test::CasePose::Ransac, hbos_test::CasePose::PerturbedGt}) {
    std::vector<double> all, rej, ra, ba;
    long st = 0, be = 0, ev = 0, evb = 0;
    for (const auto& f : hbos_test::list_case_folders(argv[1])) {
      auto c = hbos_test::load_screening_case(f, pose);
      if (c.is_static()) continue;
      auto d = hbos_test::static_disagreement(c, noisy);
      all.insert(all.end(), d.all_reference.begin(), d.all_reference.end());
      rej.insert(rej.end(), d.evidence_reference.begin(), d.evidence_reference.end());
      ra.insert(ra.end(), d.evidence_along_person.begin(), d.evidence_along_person.end());
      ba.insert(ba.end(), d.beside_along_person.begin(), d.beside_along_person.end());
      st += d.statics;
      be += d.beside_person;
      ev += d.only_default_by_evidence;
      evb += d.only_default_by_evidence_beside;
    }
    std::printf("evidence-only %ld ratio %.2f (need 1.8) beside %.2f (need 4) along %.2f vs %.2f\n",
                ev, hbos_test::median_of(rej) / hbos_test::median_of(all),
                (double(evb) / ev) / (double(be) / st), hbos_test::median_of(ra),
                hbos_test::median_of(ba));
  }
}
