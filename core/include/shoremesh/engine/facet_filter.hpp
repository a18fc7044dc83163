#pragma once
// Which vertices bound an operation's cell, as a Bloom filter: removing a vertex can change what the
// operation decided only if its bisector bounds the cell (or it was the nearest neighbour). A false
// "maybe" only reruns the operation, which then decides the same; a vertex of the set always tests
// positive. With n vertices in it, k bits each in W words, it answers "maybe" for a vertex outside it at
// a rate of about (1 - e^(-k n / 64 W))^k. One bit in one word (the filter this replaces) did so for
// 15 % of the removed vertices near a 3D cell that do not bound it, about 100 reruns per update; these
// filters measure 1.6 % in 3D (n about 15) and 0.8 % in 2D (n about 7).
#include <array>
#include <bit>
#include <cstdint>

#include "shoremesh/point.hpp"

namespace shoremesh::engine {

template <int D>
class FacetFilter {
 public:
  // 2D cells have about 7 bounding vertices, 3D about 15: 6 bits in 64, and 5 in 128.
  static constexpr int kWords = D == 2 ? 1 : 2;
  static constexpr int kBitsPerVertex = D == 2 ? 6 : 5;

  // The filter that holds every vertex.
  static FacetFilter everything() {
    FacetFilter f;
    f.words_.fill(~std::uint64_t(0));
    return f;
  }
  // A vertex's key: its position's bits, mixed. A vertex keeps its place for its life, whatever its id
  // (the engine renumbers vertices by place after a build), so no key is stored beside it.
  static std::uint64_t key_of(const Point<D>& p) {
    std::uint64_t h = 0;
    for (int i = 0; i < D; ++i) h = mix(h ^ std::bit_cast<std::uint64_t>(p[i]));
    return h;
  }
  // The bits of the vertex of this key, computed once per test of many filters.
  static FacetFilter of(std::uint64_t key) {
    FacetFilter f;
    const std::uint64_t h = mix(key);
    constexpr int kIndexBits = kWords == 1 ? 6 : 7;
    for (int k = 0; k < kBitsPerVertex; ++k) {
      const unsigned bit = unsigned(h >> (k * kIndexBits)) & ((1u << kIndexBits) - 1);
      f.words_[bit >> 6] |= std::uint64_t(1) << (bit & 63);
    }
    return f;
  }
  void add(const FacetFilter& vertex) {
    for (int i = 0; i < kWords; ++i) words_[i] |= vertex.words_[i];
  }
  // Whether the vertex whose bits these are may be in the filter (surely, if it was added).
  bool may_hold(const FacetFilter& vertex) const {
    std::uint64_t missing = 0;
    for (int i = 0; i < kWords; ++i) missing |= vertex.words_[i] & ~words_[i];
    return missing == 0;
  }

 private:
  // splitmix64's finalizer: every bit of the hash depends on every bit of the input, so neighbouring
  // places (whose coordinates share their high bits) do not share filter bits.
  static std::uint64_t mix(std::uint64_t h) {
    h += 0x9E3779B97F4A7C15ull;
    h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
    return h ^ (h >> 31);
  }

  std::array<std::uint64_t, kWords> words_{};
};

}  // namespace shoremesh::engine
