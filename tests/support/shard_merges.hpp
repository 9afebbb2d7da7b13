#pragma once
/// \file
/// The other reduction orders the merge tests check a sharded fit under: range summaries merged
/// in reverse shard order, and a plan's counts merged as a pairwise tree. Any plan with
/// `count(shard)` (hbos::ShardedFit, hbos::PyodShardedFit). Test support, not part of the library.

#include <hbos/merge.hpp>

#include <cstddef>
#include <vector>

namespace hbos::test {

/// The shards' range summaries, merged from the last shard to the first.
template <class Shard>
RangeSummary<typename Shard::Scalar> range_merged_in_reverse(const std::vector<Shard>& shards) {
  RangeSummary<typename Shard::Scalar> range;
  for (auto it = shards.rbegin(); it != shards.rend(); ++it)
    range = merge(summarize_range(*it), range);
  return range;
}

/// The plan's counts of every shard, merged pairwise as a tree (right operand first).
template <class Plan, class Shard>
CountSummary counts_merged_as_tree(const Plan& plan, const std::vector<Shard>& shards) {
  std::vector<CountSummary> counts;
  for (const auto& s : shards) counts.push_back(plan.count(s));
  while (counts.size() > 1) {
    std::vector<CountSummary> next;
    for (std::size_t i = 0; i < counts.size(); i += 2)
      next.push_back(i + 1 < counts.size() ? merge(counts[i + 1], counts[i]) : counts[i]);
    counts = next;
  }
  return counts.front();
}

}  // namespace hbos::test
