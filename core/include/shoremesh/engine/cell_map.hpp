#pragma once
// Open-addressing hash map from a quadtree cell (level + integer coordinates, packed into 128 bits) to
// its node. It lets a query jump straight to the cells around a point at any level, which keeps every
// neighbour search O(1) under the algorithm's invariants instead of O(depth) from the root.
#include <array>
#include <cstdint>
#include <vector>

#include "shoremesh/engine/ids.hpp"

namespace shoremesh::engine {

using CellKey = unsigned __int128;

// Levels go up to 40 (cells of side 2^-40 of the box): 3 x 40 coordinate bits plus the level fit 128 bits.
inline constexpr int kMaxLevel = 40;

template <int D>
inline CellKey make_cell_key(int level, const std::array<std::uint64_t, D>& coords) {
  CellKey key = CellKey(level + 1) << 122;  // never zero: zero marks an empty slot
  for (int i = 0; i < D; ++i) key |= CellKey(coords[i]) << (40 * i);
  return key;
}

class CellMap {
 public:
  CellMap() { rehash(64); }

  NodeId find(CellKey key) const {
    for (std::size_t i = slot_of(key);; i = (i + 1) & mask_) {
      if (slots_[i].key == key) return slots_[i].node;
      if (slots_[i].key == 0) return kNoNode;
    }
  }

  void insert(CellKey key, NodeId node) {
    if (2 * (size_ + 1) > slots_.size()) rehash(2 * slots_.size());
    place(key, node);
  }

  void erase(CellKey key) {
    std::size_t i = slot_of(key);
    while (slots_[i].key != key) {
      if (slots_[i].key == 0) return;
      i = (i + 1) & mask_;
    }
    // Backward-shift deletion: keeps probe sequences intact without tombstones.
    for (std::size_t j = (i + 1) & mask_;; j = (j + 1) & mask_) {
      if (slots_[j].key == 0) break;
      std::size_t home = slot_of(slots_[j].key);
      bool movable = (j > i) ? (home <= i || home > j) : (home <= i && home > j);
      if (movable) {
        slots_[i] = slots_[j];
        i = j;
      }
    }
    slots_[i] = Slot{};
    --size_;
  }

  void clear() {
    slots_.assign(64, Slot{});
    mask_ = 63;
    size_ = 0;
  }
  std::size_t size() const { return size_; }
  std::size_t memory_bytes() const { return slots_.capacity() * sizeof(Slot); }

 private:
  struct Slot {
    CellKey key = 0;
    NodeId node = kNoNode;
  };

  std::size_t slot_of(CellKey key) const {
    std::uint64_t h = std::uint64_t(key) ^ (std::uint64_t(key >> 64) * 0x9E3779B97F4A7C15ull);
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 29;
    return std::size_t(h) & mask_;
  }
  void place(CellKey key, NodeId node) {
    std::size_t i = slot_of(key);
    while (slots_[i].key != 0 && slots_[i].key != key) i = (i + 1) & mask_;
    if (slots_[i].key == 0) ++size_;
    slots_[i] = Slot{key, node};
  }
  void rehash(std::size_t capacity) {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(capacity, Slot{});
    mask_ = capacity - 1;
    size_ = 0;
    for (const Slot& s : old)
      if (s.key != 0) place(s.key, s.node);
  }

  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
  std::size_t size_ = 0;
};

}  // namespace shoremesh::engine
