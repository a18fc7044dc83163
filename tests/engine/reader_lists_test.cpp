// The engine's reader lists: one block per node's list in one array, blocks given back reused by the
// next list of their size class.
#include "shoremesh/engine/reader_lists.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

namespace shoremesh::engine {
namespace {

std::vector<std::uint32_t> as_vector(std::span<const std::uint32_t> s) { return {s.begin(), s.end()}; }

TEST(ReaderLists, SizeClassesGrowByAQuarter) {
  const std::vector<std::uint32_t> expected = {0, 1, 2, 3, 4, 5, 6, 7, 8, 10, 12, 14, 16, 20, 24, 28, 32, 40};
  for (std::uint32_t c = 0; c < expected.size(); ++c) EXPECT_EQ(ReaderLists::class_capacity(c), expected[c]) << c;
  for (std::uint32_t length = 0; length < 5000; ++length) {
    const std::uint32_t c = ReaderLists::class_of(length);
    EXPECT_GE(ReaderLists::class_capacity(c), length) << length;
    if (c > 0) {
      EXPECT_LT(ReaderLists::class_capacity(c - 1), length) << length;
    }
  }
}

// Random pushes, erases and clears against a vector per node, laid out again now and then: the lists
// read the same, no id is lost or duplicated, and every block is a list's or free.
TEST(ReaderLists, MatchAVectorPerNodeThroughRandomEdits) {
  std::mt19937 rng(7);
  ReaderLists lists;
  std::vector<std::vector<std::uint32_t>> model;
  std::uint32_t next_id = 0;
  for (int step = 0; step < 40000; ++step) {
    if (step % 5000 == 0) {
      model.resize(model.size() + 50);
      lists.grow_to(model.size());
    }
    const std::size_t n = rng() % model.size();
    const unsigned what = rng() % 10;
    if (what < 6) {
      lists.push(n, next_id);
      model[n].push_back(next_id++);
    } else if (what < 9) {
      if (model[n].empty()) {
        EXPECT_FALSE(lists.erase(n, 12345678));
        continue;
      }
      const std::size_t k = rng() % model[n].size();
      const std::uint32_t id = model[n][k];
      EXPECT_TRUE(lists.erase(n, id));
      model[n][k] = model[n].back();
      model[n].pop_back();
    } else {
      lists.clear(n);
      model[n].clear();
    }
    if (step % 9973 == 0) lists.lay_out();
    if (step % 997 == 0) {
      ASSERT_EQ(lists.live_block_entries() + lists.free_entries(), lists.size()) << step;
      for (std::size_t m = 0; m < model.size(); ++m) ASSERT_EQ(as_vector(lists.list(m)), model[m]) << m;
    }
  }
  lists.rename([](std::uint32_t id) { return id + 1; });
  for (std::size_t m = 0; m < model.size(); ++m) {
    for (std::uint32_t& id : model[m]) ++id;
    EXPECT_EQ(as_vector(lists.list(m)), model[m]);
  }
}

// A list that leaves a block of its class and one that needs that class next take the same block:
// taking and giving back in turn does not grow the array.
TEST(ReaderLists, BlocksGivenBackAreTakenAgain) {
  ReaderLists lists;
  lists.grow_to(2);
  for (std::uint32_t k = 0; k < 6; ++k) lists.push(0, k);
  const std::size_t size = lists.size();
  for (int round = 0; round < 100; ++round) {
    lists.clear(0);
    for (std::uint32_t k = 0; k < 6; ++k) lists.push(1, k);
    lists.clear(1);
    for (std::uint32_t k = 0; k < 6; ++k) lists.push(0, k);
  }
  EXPECT_EQ(lists.size(), size);
  EXPECT_EQ(as_vector(lists.list(0)), (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5}));
}

// Laid out, each list sits in node order with room to grow: one more push moves nothing.
TEST(ReaderLists, LayOutKeepsNodeOrderAndRoom) {
  ReaderLists lists;
  lists.grow_to(3);
  for (std::uint32_t k = 0; k < 10; ++k) lists.push(2 - k % 3, k);
  lists.lay_out();
  const std::uint32_t* first = lists.list(0).data();
  EXPECT_LT(first, lists.list(1).data());
  EXPECT_LT(lists.list(1).data(), lists.list(2).data());
  lists.push(0, 100);
  EXPECT_EQ(lists.list(0).data(), first);
  EXPECT_EQ(lists.free_entries(), 0u);
}

}  // namespace
}  // namespace shoremesh::engine
