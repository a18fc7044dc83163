// The pool of the engine's children and reads runs: a run given back leaves a block that the next run of
// its size class takes, so the pool follows the live runs without a compaction.
#include "shoremesh/engine/block_pool.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

namespace shoremesh::engine {
namespace {

std::vector<std::uint32_t> run_of(std::uint32_t length, std::uint32_t first) {
  std::vector<std::uint32_t> run(length);
  for (std::uint32_t k = 0; k < length; ++k) run[k] = first + k;
  return run;
}

TEST(BlockPool, RunsReadBackAsWritten) {
  BlockPool pool;
  const auto a = run_of(3, 10), b = run_of(40, 100);
  const std::uint32_t at_a = pool.allocate(a), at_b = pool.allocate(b);
  EXPECT_EQ(std::vector<std::uint32_t>(pool.run(at_a, at_a + 3).begin(), pool.run(at_a, at_a + 3).end()), a);
  EXPECT_EQ(std::vector<std::uint32_t>(pool.run(at_b, at_b + 40).begin(), pool.run(at_b, at_b + 40).end()), b);
  EXPECT_EQ(pool.size(), 3u + 64u);  // exact up to 32 entries, then the next power of two
}

TEST(BlockPool, AReleasedBlockIsTakenByTheNextRunOfItsClass) {
  BlockPool pool;
  const std::uint32_t first = pool.allocate(run_of(5, 0));
  pool.allocate(run_of(5, 50));
  pool.release(first, 5);
  EXPECT_EQ(pool.free_entries(), 5u);
  // Another size does not take it; the same size does, and the pool does not grow.
  const std::uint32_t other = pool.allocate(run_of(4, 7));
  EXPECT_NE(other, first);
  EXPECT_EQ(pool.allocate(run_of(5, 9)), first);
  EXPECT_EQ(pool.free_entries(), 0u);
  EXPECT_EQ(pool.size(), 14u);
  // Runs of 33 to 64 entries share the class of 64.
  const std::uint32_t long_run = pool.allocate(run_of(33, 0));
  pool.release(long_run, 33);
  EXPECT_EQ(pool.allocate(run_of(60, 0)), long_run);
  EXPECT_EQ(pool[long_run], 0u);
  EXPECT_EQ(pool[long_run + 59], 59u);
}

TEST(BlockPool, EmptyRunsTakeNoRoom) {
  BlockPool pool;
  pool.allocate({});
  pool.release(0, 0);
  EXPECT_EQ(pool.size(), 0u);
  EXPECT_EQ(pool.free_entries(), 0u);
}

// A steady churn, as in a long edit session: the pool stays at the high-water mark of its live runs.
TEST(BlockPool, SteadyChurnDoesNotGrowThePool) {
  BlockPool pool;
  std::mt19937 rng(5);
  struct Live {
    std::uint32_t begin, length;
  };
  std::vector<Live> live;
  for (int k = 0; k < 1000; ++k) {
    const std::uint32_t length = 1 + rng() % 12;
    live.push_back({pool.allocate(run_of(length, std::uint32_t(k))), length});
  }
  const std::size_t after_build = pool.size();
  for (int step = 0; step < 100000; ++step) {
    const std::size_t k = rng() % live.size();
    pool.release(live[k].begin, live[k].length);
    const std::uint32_t length = live[k].length;  // a rerun mostly writes as many as before
    live[k] = {pool.allocate(run_of(length, std::uint32_t(step))), length};
    ASSERT_EQ(pool[live[k].begin], std::uint32_t(step));
  }
  EXPECT_EQ(pool.size(), after_build);
  std::size_t live_entries = 0;
  for (const Live& l : live) live_entries += l.length;
  EXPECT_EQ(live_entries + pool.free_entries(), pool.size());
}

}  // namespace
}  // namespace shoremesh::engine
