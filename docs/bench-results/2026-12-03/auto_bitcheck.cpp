// The before/after check and the callgrind job of docs/benchmarks.md ("n_bins='auto', 2026-12-03").
// Not part of the build. Compile it once against the old headers and once against the new:
//
//   g++ -std=c++17 -O3 -DNDEBUG -g -isystem /usr/include/eigen3 -I<include dir> auto_bitcheck.cpp
//   ./a.out check   # every chosen b (double, float, strides 1 and 2, max_bins 65536 and 7) and a
//                   # hash of the auto fit_and_score scores; the two outputs must be identical
//   valgrind --tool=callgrind ./a.out bench 1   # 1e6 x 2 row-major N(0, 1), as the Python module
// Driver: "bench" = 1e6x2 row-major N(0,1) fit_and_score auto (as the python module);
// "check" = digest of birge_rozenblac_bins and fit_and_score on varied data.
#include <cstdio>
#include <cstring>
#include <hbos/hbos.hpp>
#include <random>
#include <string>
#include <vector>

using Strided = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
using StridedF =
    Eigen::Map<const Eigen::MatrixXf, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;

static std::uint64_t fnv(const void* p, std::size_t n, std::uint64_t h = 1469598103934665603ULL) {
  const auto* c = static_cast<const unsigned char*>(p);
  for (std::size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ULL;
  return h;
}

static std::vector<double> make(int kind, std::size_t n, std::mt19937_64& g) {
  std::vector<double> v(n);
  std::normal_distribution<double> nd;
  std::uniform_real_distribution<double> ud;
  std::cauchy_distribution<double> cd;
  for (std::size_t i = 0; i < n; ++i) {
    switch (kind) {
      case 0:
        v[i] = nd(g);
        break;
      case 1:
        v[i] = ud(g);
        break;
      case 2:
        v[i] = static_cast<double>(g() % 7);
        break;  // heavy ties
      case 3:
        v[i] = 3.25;
        break;  // constant
      case 4:
        v[i] = cd(g);
        break;  // heavy tails
      case 5:
        v[i] = std::exp(3 * nd(g));
        break;   // lognormal
      case 6: {  // exactly on edges of many candidates: j / L with L = lcm-ish
        const std::uint64_t L = 720720;
        v[i] = static_cast<double>(g() % (L + 1)) / static_cast<double>(L);
        break;
      }
      case 7: {  // on and next to edges k/b for random b, k
        const double b = static_cast<double>(2 + g() % 1000);
        const double k = static_cast<double>(g() % static_cast<std::uint64_t>(b + 1));
        double x = k / b;
        const int w = static_cast<int>(g() % 3);
        if (w == 1) x = std::nextafter(x, 2.0);
        if (w == 2) x = std::nextafter(x, -1.0);
        v[i] = std::min(1.0, std::max(0.0, x));
        break;
      }
      case 8:
        v[i] = (g() % 2) ? -1e300 : 1e300 * ud(g);
        break;  // extreme range (scale)
      case 9:
        v[i] = 1e-310 * ud(g);
        break;  // subnormal
      case 10:
        v[i] = static_cast<double>(g() % 1000) * 0.001 - 0.5;
        break;  // grid
      case 11:
        v[i] = (g() % 100 == 0) ? 1e6 * nd(g) : nd(g);
        break;  // outliers
      default:
        v[i] = std::floor(nd(g) * 100.0) / 7.0;
        break;
    }
  }
  if (kind == 6 || kind == 7) {
    v[0] = 0.0;
    v[n - 1] = 1.0;
  }
  return v;
}

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "bench";
  if (mode == "bench") {
    const long reps = argc > 2 ? std::atol(argv[2]) : 1;
    const Eigen::Index n = 1000000;
    std::mt19937_64 g(20240611);
    std::normal_distribution<double> nd;
    std::vector<double> x(2 * n);
    for (auto& v : x) v = nd(g);
    Strided m(x.data(), n, 2, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(1, 2));
    hbos::HbosParams p;
    p.feature.binning.shifts = 1;
    p.feature.binning.rule = hbos::BinCountRule::BirgeRozenblac;
    double acc = 0;
    for (long r = 0; r < reps; ++r) {
      Eigen::VectorXd out(n);
      auto model = hbos::Hbosd::fit_and_score(m, out, p);
      acc += out.sum();
    }
    std::printf("%.17g\n", acc);
    return 0;
  }
  // check
  std::uint64_t total = 0;
  const std::size_t sizes[] = {4,    5,    7,    16,    100,   255,    256,    257,     1000,
                               1023, 4096, 4100, 10007, 65536, 100000, 262147, 1048580, 2000000};
  std::vector<double> vals;
  std::vector<std::uint32_t> idx;
  for (int kind = 0; kind <= 12; ++kind) {
    for (std::size_t n : sizes) {
      if (n >= 1000000 && kind % 3 != 0 && kind != 7 && kind != 4) continue;
      std::mt19937_64 g(1234 + static_cast<std::uint64_t>(kind) * 7919 + n);
      std::vector<double> v = make(kind, n, g);
      std::vector<float> vf(v.begin(), v.end());
      for (Eigen::Index stride : {1, 2}) {
        const Eigen::Index nn = static_cast<Eigen::Index>(n) / stride;
        double lo = v[0], hi = v[0];
        for (Eigen::Index i = 0; i < nn; ++i) {
          lo = std::min(lo, v[static_cast<std::size_t>(i * stride)]);
          hi = std::max(hi, v[static_cast<std::size_t>(i * stride)]);
        }
        float lof = vf[0], hif = vf[0];
        for (Eigen::Index i = 0; i < nn; ++i) {
          lof = std::min(lof, vf[static_cast<std::size_t>(i * stride)]);
          hif = std::max(hif, vf[static_cast<std::size_t>(i * stride)]);
        }
        const double s = hbos::detail::rule_scale(lo, hi);
        const double sf =
            hbos::detail::rule_scale(static_cast<double>(lof), static_cast<double>(hif));
        for (Eigen::Index maxb : {Eigen::Index{65536}, Eigen::Index{7}}) {
          const auto b =
              hbos::detail::birge_rozenblac_bins(v.data(), nn, stride, lo, hi, maxb, vals, idx, s);
          const auto bf = hbos::detail::birge_rozenblac_bins(vf.data(), nn, stride, lof, hif, maxb,
                                                             vals, idx, sf);
          std::printf("kind %d n %zu stride %ld maxb %ld: b %ld bf %ld\n", kind, n, (long)stride,
                      (long)maxb, (long)b, (long)bf);
          total = fnv(&b, sizeof b, total);
          total = fnv(&bf, sizeof bf, total);
        }
        if (n <= 262147 || kind == 0) {
          // full fit_and_score, 2 columns interleaved (C order), double and float
          const Eigen::Index rows = static_cast<Eigen::Index>(n) / 2;
          hbos::HbosParams p;
          p.feature.binning.shifts = 1;
          p.feature.binning.rule = hbos::BinCountRule::BirgeRozenblac;
          try {
            Strided m(v.data(), rows, 2, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(1, 2));
            Eigen::VectorXd out(rows);
            auto model = hbos::Hbosd::fit_and_score(m, out, p);
            total = fnv(out.data(), sizeof(double) * static_cast<std::size_t>(rows), total);
            StridedF mf(vf.data(), rows, 2, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(1, 2));
            Eigen::VectorXf outf(rows);
            auto modelf = hbos::Hbosf::fit_and_score(mf, outf, p);
            total = fnv(outf.data(), sizeof(float) * static_cast<std::size_t>(rows), total);
            std::printf("  scores %016llx\n", (unsigned long long)total);
          } catch (const std::exception& e) {
            std::printf("  throws %s\n", e.what());
          }
        }
      }
    }
  }
  std::printf("TOTAL %016llx\n", (unsigned long long)total);
}
