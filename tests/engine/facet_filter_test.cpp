// The facet filter never misses a vertex it holds (a miss would skip a rerun the output needs), and its
// false "maybe" stays rare at the sizes cells have (each one costs a rerun).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <random>
#include <set>

#include "shoremesh/engine/facet_filter.hpp"
#include "shoremesh/engine/ids.hpp"

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

// Keys from positions (the engine's): places on a fine grid share their coordinates' high bits, and the
// grid's neighbours of the held places are the outsiders that matter (a removed vertex near the cell).
template <int D>
void holds_places_and_little_else(std::size_t size, double max_false_rate) {
  std::mt19937_64 rng(11 + D);
  std::size_t false_maybes = 0, outsiders = 0;
  auto place = [](const std::array<int, D>& c) {
    Point<D> p;
    for (int i = 0; i < D; ++i) p[i] = 0.25 + c[i] * 0x1p-20;
    return p;
  };
  for (int trial = 0; trial < 200; ++trial) {
    std::set<std::array<int, D>> held;
    while (held.size() < size) {
      std::array<int, D> c;
      for (int i = 0; i < D; ++i) c[i] = int(rng() % 6);
      held.insert(c);
    }
    FacetFilter<D> filter;
    for (const auto& c : held) filter.add(FacetFilter<D>::of(FacetFilter<D>::key_of(place(c))));
    for (const auto& c : held) ASSERT_TRUE(filter.may_hold(FacetFilter<D>::of(FacetFilter<D>::key_of(place(c)))));
    std::array<int, D> c{};
    for (;;) {
      if (!held.count(c)) {
        ++outsiders;
        if (filter.may_hold(FacetFilter<D>::of(FacetFilter<D>::key_of(place(c))))) ++false_maybes;
      }
      int i = 0;
      while (i < D && ++c[i] == 6) c[i++] = 0;
      if (i == D) break;
    }
  }
  EXPECT_LT(double(false_maybes) / double(outsiders), max_false_rate);
}

TEST(FacetFilter, HoldsEveryPlaceAddedAndRarelyAnother2D) { holds_places_and_little_else<2>(8, 0.05); }
TEST(FacetFilter, HoldsEveryPlaceAddedAndRarelyAnother3D) { holds_places_and_little_else<3>(18, 0.06); }

// About 7 vertices bound a 2D cell and 15 a 3D one: sizes a little above that, where a filter of one
// bit per vertex says "maybe" for 12 % (2D) and 25 % (3D) of the others.
TEST(FacetFilter, HoldsEveryVertexAddedAndRarelyAnother2D) { holds_what_it_was_given_and_little_else<2>(8, 0.05); }
TEST(FacetFilter, HoldsEveryVertexAddedAndRarelyAnother3D) { holds_what_it_was_given_and_little_else<3>(18, 0.06); }

}  // namespace
}  // namespace shoremesh::engine
