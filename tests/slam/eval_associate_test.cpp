// associate(): associate.py's semantics (strict |dt| < max_difference, greedy by |dt| with ties
// broken by stamps, one-to-one, sorted by ground truth), checked on hand-made edge cases and
// against a literal O(n·m) transcription of the rule on random stamps.
#include "eval/associate.hpp"

#include <catch2/catch.hpp>
#include <hbos/error.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

using Catch::Matchers::Contains;
using hbos::slam::associate;
using hbos::slam::AssociationParams;
using hbos::slam::Match;

namespace {

using Pairs = std::vector<std::pair<Eigen::Index, Eigen::Index>>;

Pairs as_pairs(const std::vector<Match>& matches) {
  Pairs pairs;
  for (const Match& m : matches) pairs.emplace_back(m.gt, m.est);
  return pairs;
}

AssociationParams with(double max_difference, double offset = 0.0) {
  AssociationParams p;
  p.max_difference = max_difference;
  p.offset = offset;
  return p;
}

// The rule as associate.py states it: all candidate tuples, sorted, accepted greedily.
Pairs brute_force(const std::vector<double>& a, const std::vector<double>& b, double max_difference,
                  double offset) {
  std::vector<std::tuple<double, double, double, Eigen::Index, Eigen::Index>> candidates;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      const double d = std::abs(a[i] - (b[j] + offset));
      if (d < max_difference) {
        candidates.emplace_back(d, a[i], b[j], static_cast<Eigen::Index>(i),
                                static_cast<Eigen::Index>(j));
      }
    }
  }
  std::sort(candidates.begin(), candidates.end());
  std::set<Eigen::Index> used_a;
  std::set<Eigen::Index> used_b;
  Pairs pairs;
  for (const auto& [d, sa, sb, i, j] : candidates) {
    if (used_a.count(i) > 0 || used_b.count(j) > 0) continue;
    used_a.insert(i);
    used_b.insert(j);
    pairs.emplace_back(i, j);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace

TEST_CASE("associate: |dt| must be strictly below max_difference", "[eval][associate]") {
  // 0.0 and 0.02 differ by exactly the double 0.02: not a pair.
  CHECK(associate({0.0}, {0.02}, with(0.02)).empty());
  CHECK(associate({0.02}, {0.0}, with(0.02)).empty());
  // One ulp closer is a pair.
  CHECK(as_pairs(associate({0.0}, {std::nextafter(0.02, 0.0)}, with(0.02))) == Pairs{{0, 0}});
  // Real TUM stamps written 0.02 s apart are not 0.02 apart in binary: at 1.3e9 s a double
  // resolves 2.4e-7 s, and 1305031102.1758 − 1305031102.1558 = 0.019999980926513672 < 0.02, so
  // the script (and we) pair them. The double arithmetic decides, not the decimal intent.
  const double a = 1305031102.1558;
  const double b = 1305031102.1758;
  CHECK(b - a == 0.019999980926513672);
  CHECK(as_pairs(associate({a}, {b}, with(0.02))) == Pairs{{0, 0}});
  CHECK(associate({a}, {1305031102.1759}, with(0.02)).empty());
}

TEST_CASE("associate: greedy by |dt|, one-to-one", "[eval][associate]") {
  // Both ground-truth stamps are within range of the single estimate stamp; the nearer wins and
  // the other stays unmatched (a nearest-neighbour matcher such as evo's would match both).
  CHECK(as_pairs(associate({1.000, 1.010}, {1.008}, with(0.02))) == Pairs{{1, 0}});
  // Conflict resolved in order of |dt|: (1.010, 1.012) first, then (1.000, 1.006); the
  // candidate (1.010, 1.006) with |dt| 0.004 loses because 1.010 is already taken.
  CHECK(as_pairs(associate({1.000, 1.010}, {1.006, 1.012}, with(0.02))) == Pairs{{0, 0}, {1, 1}});
  // Greedy is not a maximum matching: (0.5, 0.5) is taken first and blocks both others.
  CHECK(as_pairs(associate({0.5, 0.875}, {0.125, 0.5}, with(0.5))) == Pairs{{0, 1}});
  // Equal |dt| (exact binary values): the smaller ground-truth stamp wins, like tuple sorting.
  CHECK(as_pairs(associate({0.0, 0.5}, {0.25}, with(0.3))) == Pairs{{0, 0}});
  // ... and then the smaller estimate stamp.
  CHECK(as_pairs(associate({0.25}, {0.0, 0.5}, with(0.3))) == Pairs{{0, 0}});
}

TEST_CASE("associate: sorted output, offsets, empty inputs and bad input", "[eval][associate]") {
  // Accepted in the order (1, 1), (2, 2), (0, 0) by |dt|; returned sorted by ground truth.
  CHECK(as_pairs(associate({0.0, 1.0, 2.0}, {0.011, 1.0, 2.001}, with(0.02))) ==
        Pairs{{0, 0}, {1, 1}, {2, 2}});
  // The offset is added to the estimate stamps.
  CHECK(as_pairs(associate({10.0, 11.0}, {0.0, 1.0}, with(0.02, 10.0))) == Pairs{{0, 0}, {1, 1}});
  CHECK(associate({10.0, 11.0}, {0.0, 1.0}, with(0.02)).empty());
  CHECK(associate({}, {1.0}, with(0.02)).empty());
  CHECK(associate({1.0}, {}, with(0.02)).empty());
  // Duplicated or unsorted stamps are the reader's job to reject or resolve; here they are a
  // precondition violation with a clear message.
  CHECK_THROWS_WITH(
      associate({0.0, 1.0, 1.0}, {0.5}, with(0.02)),
      Contains("ground-truth stamps must strictly increase") && Contains("stamp 2 = 1 follows 1"));
  CHECK_THROWS_WITH(associate({0.0}, {2.001, 0.01}, with(0.02)),
                    Contains("estimate stamps must strictly increase"));
  CHECK_THROWS_WITH(associate({0.0}, {0.0}, with(-0.1)), Contains("max_difference"));
  CHECK_THROWS_WITH(associate({0.0}, {0.0}, with(std::nan(""))), Contains("max_difference"));
  CHECK_THROWS_WITH(associate({0.0}, {0.0}, with(0.02, INFINITY)), Contains("offset"));
}

TEST_CASE("associate equals the literal O(n·m) rule on random stamps", "[eval][associate]") {
  for (unsigned seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> step(0.0005, 0.04);
    std::uniform_real_distribution<double> jitter(-0.015, 0.015);
    std::vector<double> gt;
    std::vector<double> est;
    double t = 1305031098.6659;
    for (int i = 0; i < 300; ++i) gt.push_back(t += step(rng));
    for (std::size_t i = 0; i < gt.size(); i += 1 + rng() % 3) {
      // Some estimate stamps exactly on a GT stamp or exactly max_difference away.
      const unsigned kind = static_cast<unsigned>(rng() % 5);
      const double s = kind == 0 ? gt[i] : kind == 1 ? gt[i] + 0.02 : gt[i] + jitter(rng);
      if (est.empty() || s > est.back()) est.push_back(s);
    }
    const double max_difference = seed % 2 == 0 ? 0.02 : 0.01;
    const double offset = seed % 3 == 0 ? 0.0 : jitter(rng);
    INFO("seed " << seed << ", offset " << offset);
    const Pairs expected = brute_force(gt, est, max_difference, offset);
    CHECK(as_pairs(associate(gt, est, with(max_difference, offset))) == expected);
    CHECK(expected.size() > 20);  // the random case is not trivially empty
  }
}
