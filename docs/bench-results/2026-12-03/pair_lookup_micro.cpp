// The pair-table scoring kernel alone (detail::lookup_byte_pairs), baseline against AVX2, on
// n rows of two features with 10 one-byte bins each, in blocks of 2048 rows as
// fit_and_score_columns calls it; best of 80 interleaved runs, ms. The output of every run is
// checked against the baseline's. Build: g++ -O3 -DNDEBUG -std=c++17 -I include this.cpp
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "hbos/detail/byte_bins.hpp"
using namespace hbos::detail;

int main(int argc, char** argv) {
  const std::size_t n = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 1000000, k = 10;
  std::mt19937_64 rng(1);
  std::vector<std::uint8_t> b(2 * n);
  for (auto& v : b) v = static_cast<std::uint8_t>(rng() % k);
  std::vector<double> table(k * k);
  for (std::size_t i = 0; i < table.size(); ++i) table[i] = 0.1 * double(i) + 1e-3;
  std::vector<double> out(n), ref(n);
  const char* names[] = {"baseline", "avx2", "baseline streamed", "avx2 asked to stream"};
  auto run = [&](int variant) {
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t start = 0; start < n; start += 2048) {
      const std::size_t m = std::min<std::size_t>(2048, n - start);
      const std::uint8_t* b0 = b.data() + start;
      lookup_byte_pairs(table.data(), b0, b0 + n, k, m, out.data() + start, variant >= 2,
                        variant % 2 == 0 ? Isa::Baseline : Isa::Avx2);
    }
    fence_streaming_stores();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  };
  run(0);
  ref = out;
  double best[4] = {1e9, 1e9, 1e9, 1e9};
  for (int rep = 0; rep < 80; ++rep)
    for (int v = 0; v < 4; ++v) {
      best[v] = std::min(best[v], run(v));
      if (out != ref) std::printf("MISMATCH %s\n", names[v]);
    }
  std::printf("n=%zu:", n);
  for (int v = 0; v < 4; ++v) std::printf("  %s %.3f", names[v], best[v]);
  std::printf(" ms\n");
}
