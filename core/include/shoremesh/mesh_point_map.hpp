#pragma once
// A map from exact points to values in one flat array (open addressing, linear probing): what the mesh's
// updates look their vertices up in. A node-based std::unordered_map costs a bucket load, a node load and
// a division per look-up and an allocation per point; here a look-up is a multiplication and a run of
// adjacent slots (24 bytes each in 2D with a pointer value, at most 3/4 full).
//
// A value equal to V{} marks an empty slot: values put in must differ from it (a vertex handle is never
// null). Erasing shifts the run after the slot back (no tombstones), so look-ups stay short after any
// number of edits.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include "shoremesh/point.hpp"

namespace shoremesh {

template <int D, class V>
class PointMap {
 public:
  // Room for n points without growing.
  void reserve(std::size_t n) {
    std::size_t capacity = 16;
    while (capacity * 3 < n * 4) capacity *= 2;
    if (capacity > slots_.size()) rehash(capacity);
  }
  std::size_t size() const { return size_; }

  // The value at p, or null.
  V* find(const Point<D>& p) {
    if (slots_.empty()) return nullptr;
    for (std::size_t i = home(p);; i = (i + 1) & mask_) {
      Slot& s = slots_[i];
      if (s.value == V{}) return nullptr;
      if (s.key == p) return &s.value;
    }
  }
  const V* find(const Point<D>& p) const { return const_cast<PointMap*>(this)->find(p); }
  bool contains(const Point<D>& p) const { return find(p) != nullptr; }
  V& at(const Point<D>& p) {
    if (V* v = find(p)) return *v;
    throw std::out_of_range("PointMap::at: no such point");
  }

  // Puts (p, value) in unless p is there already; whether it did.
  bool emplace(const Point<D>& p, const V& value) {
    if ((size_ + 1) * 4 > slots_.size() * 3) rehash(slots_.empty() ? 16 : 2 * slots_.size());
    for (std::size_t i = home(p);; i = (i + 1) & mask_) {
      Slot& s = slots_[i];
      if (s.value == V{}) {
        s = {p, value};
        ++size_;
        return true;
      }
      if (s.key == p) return false;
    }
  }

  // Takes p out (if there); whether it was there.
  bool erase(const Point<D>& p) {
    if (slots_.empty()) return false;
    std::size_t i = home(p);
    for (;; i = (i + 1) & mask_) {
      if (slots_[i].value == V{}) return false;
      if (slots_[i].key == p) break;
    }
    // Backward shift: a later slot of the run moves into the hole unless its home lies after the hole
    // (cyclically, in (hole, j]), where a look-up from its home would not pass the hole.
    for (std::size_t j = (i + 1) & mask_;; j = (j + 1) & mask_) {
      Slot& s = slots_[j];
      if (s.value == V{}) break;
      const std::size_t h = home(s.key);
      if (((j - h) & mask_) >= ((j - i) & mask_)) {
        slots_[i] = s;
        i = j;
      }
    }
    slots_[i] = Slot{};
    --size_;
    return true;
  }

 private:
  struct Slot {
    Point<D> key{};
    V value{};
  };

  std::size_t home(const Point<D>& p) const {
    // The points' own hash (-0 as +0), mixed so that its high bits, the slot, depend on every bit.
    const std::uint64_t h = PointHash<D>{}(p);
    return static_cast<std::size_t>((h ^ (h >> 29)) * 0xBF58476D1CE4E5B9ull >> shift_);
  }

  void rehash(std::size_t capacity) {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(capacity, Slot{});
    mask_ = capacity - 1;
    shift_ = 64 - std::countr_zero(capacity);
    size_ = 0;
    for (const Slot& s : old)
      if (!(s.value == V{})) emplace(s.key, s.value);
  }

  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
  int shift_ = 64;
  std::size_t size_ = 0;
};

}  // namespace shoremesh
