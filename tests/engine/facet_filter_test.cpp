// The facet filter never misses a vertex it holds (a miss would skip a rerun the output needs), and its
// false "maybe" stays rare at the sizes cells have (each one costs a rerun).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <set>

#include "shoremesh/engine/facet_filter.hpp"

namespace shoremesh::engine {
namespace {

template <int D>
void holds_what_it_was_given_and_little_else(std::size_t size, double max_false_rate) {
  std::mt19937_64 rng(7 + D);
  std::size_t false_maybes = 0, outsiders = 0;
  for (int trial = 0; trial < 200; ++trial) {
    FacetFilter<D> filter;
    std::set<VertexId> held;
    // Ids close together as well as far apart: Steiner vertices born together are often neighbours.
    const auto base = VertexId(rng() % 1000000);
    while (held.size() < size) held.insert(base + VertexId(rng() % (trial % 2 == 0 ? 64 : 1000000)));
    for (VertexId w : held) filter.add(FacetFilter<D>::of(w));
    for (VertexId w : held) ASSERT_TRUE(filter.may_hold(FacetFilter<D>::of(w))) << "vertex " << w;
    for (VertexId w = base; w < base + 200; ++w) {
      if (held.count(w)) continue;
      ++outsiders;
      if (filter.may_hold(FacetFilter<D>::of(w))) ++false_maybes;
    }
    ASSERT_TRUE(FacetFilter<D>::everything().may_hold(FacetFilter<D>::of(base)));
    ASSERT_FALSE(FacetFilter<D>{}.may_hold(FacetFilter<D>::of(base)));
  }
  EXPECT_LT(double(false_maybes) / double(outsiders), max_false_rate);
}

// About 7 vertices bound a 2D cell and 15 a 3D one: sizes a little above that, where a filter of one
// bit per vertex says "maybe" for 12 % (2D) and 25 % (3D) of the others.
TEST(FacetFilter, HoldsEveryVertexAddedAndRarelyAnother2D) { holds_what_it_was_given_and_little_else<2>(8, 0.05); }
TEST(FacetFilter, HoldsEveryVertexAddedAndRarelyAnother3D) { holds_what_it_was_given_and_little_else<3>(18, 0.06); }

}  // namespace
}  // namespace shoremesh::engine
