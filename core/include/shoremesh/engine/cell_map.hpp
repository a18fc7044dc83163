#pragma once
// Open-addressing hash map from a quadtree cell (level + integer coordinates) to a node id: the quadtree
// keeps each internal node's cell with its children's block (so a node is found from its parent's
// entry, 2^D times fewer entries than nodes). It lets a query jump straight to the cells around a point
// at any level, which keeps every neighbour search O(1) under the algorithm's invariants instead of
// O(depth) from the root.
//
// Two tables: cells of the levels whose D coordinates fit one 64-bit word with a marker bit (2D: levels
// <= 31, 3D: <= 21; every cell of a uniform input of up to ~10^9 points) are keyed by that word in
// 16-byte slots; deeper cells (inputs closer than 2^-31 of the box in 2D) by 128 bits in a second table.
// Half the slot of a 128-bit key: the table is the tree's largest part after the nodes, and a look-up's
// probes stay within one cache line more often.
#include <array>
#include <atomic>
#include <cstdint>
#include <vector>

#include "shoremesh/engine/ids.hpp"

namespace shoremesh::engine {

// A GCC/Clang extension type; __extension__ says so to -Wpedantic.
__extension__ typedef unsigned __int128 CellKey;

// Levels go up to 40 (cells of side 2^-40 of the box): 3 x 40 coordinate bits plus the level fit 128 bits.
inline constexpr int kMaxLevel = 40;

template <int D>
inline CellKey make_cell_key(int level, const std::array<std::uint64_t, D>& coords) {
  CellKey key = CellKey(level + 1) << 122;  // never zero: zero marks an empty slot
  for (int i = 0; i < D; ++i) key |= CellKey(coords[i]) << (40 * i);
  return key;
}

// The deepest level whose cells have a 64-bit key: D coordinates of `level` bits and a marker bit above.
template <int D>
inline constexpr int kCompactLevels = 63 / D;

// 2^(D level) + the coordinates side by side, `level` bits each: the marker's place names the level, so
// keys of different levels differ, and none is zero.
template <int D>
inline std::uint64_t compact_cell_key(int level, const std::array<std::uint64_t, D>& coords) {
  std::uint64_t key = std::uint64_t(1) << (D * level);
  for (int i = 0; i < D; ++i) key |= coords[i] << (level * i);
  return key;
}

namespace detail {

inline std::uint64_t mix_hash(std::uint64_t h) {
  h ^= h >> 31;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 29;
  return h;
}
inline std::uint64_t hash_key(std::uint64_t key) { return mix_hash(key * 0x9E3779B97F4A7C15ull); }
inline std::uint64_t hash_key(CellKey key) {
  return mix_hash(std::uint64_t(key) ^ (std::uint64_t(key >> 64) * 0x9E3779B97F4A7C15ull));
}

// Unique among all tables of the process (64 bits never wrap): an answer about one table never
// passes for another's.
inline std::uint64_t next_generation() {
  static std::atomic<std::uint64_t> last{0};
  return last.fetch_add(1, std::memory_order_relaxed) + 1;
}

// Linear probing at most half full, backward-shift deletion; key 0 marks an empty slot. Any number of
// slots (a hash's low 32 bits scaled to it picks the first): a build reserves what its cells need. At
// Superior (591,396 cells) 1.48 million slots of 12 bytes, 17.7 MB, where the next power of two of
// 16-byte slots took 33.6 MB.
template <class Key>
class CellTable {
 public:
  explicit CellTable(std::size_t capacity) { rehash(capacity); }
  // A copy shares the recent answers of its original until either changes; a moved-from table has none.
  CellTable(const CellTable&) = default;
  CellTable& operator=(const CellTable&) = default;
  CellTable(CellTable&& other) noexcept
      : slots_(std::move(other.slots_)), size_(other.size_), generation_(other.generation_) {
    other.generation_ = next_generation();
  }
  CellTable& operator=(CellTable&& other) noexcept {
    slots_ = std::move(other.slots_);
    size_ = other.size_;
    generation_ = other.generation_;
    other.generation_ = next_generation();
    return *this;
  }

  NodeId find(Key key) const {
    const std::uint64_t h = hash_key(key);
    RecentEntry& recent = recent_table()[h >> (64 - kRecentBits)];
    if (recent.key == key && recent.generation == generation_) return recent.node;
    NodeId node = kNoNode;
    for (std::size_t i = slot_of_hash(h);; i = next(i)) {
      if (slots_[i].key == key) {
        node = slots_[i].node;
        break;
      }
      if (slots_[i].key == 0) break;
    }
    recent = RecentEntry{key, node, generation_};
    return node;
  }

  // Fetches the slot where key's probe starts (a table far larger than the caches).
  void prefetch(Key key) const { __builtin_prefetch(&slots_[slot_of(key)], 1); }

  void insert(Key key, NodeId node) {
    changed();
    if (2 * (size_ + 1) > slots_.size()) rehash(2 * slots_.size());
    place(key, node);
  }

  void erase(Key key) {
    changed();
    std::size_t i = slot_of(key);
    while (slots_[i].key != key) {
      if (slots_[i].key == 0) return;
      i = next(i);
    }
    // Backward-shift deletion: keeps probe sequences intact without tombstones.
    for (std::size_t j = next(i);; j = next(j)) {
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

  // Room for `count` keys without a rehash on the way (a build that knows its size up front), and for
  // `spare` more after those: 40 % full then (the look-ups of cells that do not exist, which every
  // neighbour search makes, probe further in a fuller table).
  void reserve(std::size_t count, std::size_t spare) {
    const std::size_t capacity = 5 * (count + spare) / 2;
    if (capacity > slots_.size()) rehash(capacity);
  }
  void clear(std::size_t capacity) {
    changed();
    slots_.assign(capacity, Slot{});
    size_ = 0;
  }
  std::size_t size() const { return size_; }
  std::size_t memory_bytes() const { return slots_.capacity() * sizeof(Slot); }

 private:
  // Packed: 12 bytes with a 64-bit key instead of 16 (a few slots straddle a cache line).
  struct __attribute__((packed)) Slot {
    Key key = 0;
    NodeId node = kNoNode;
  };

  std::size_t slot_of_hash(std::uint64_t h) const {
    return std::size_t((std::uint64_t(std::uint32_t(h)) * slots_.size()) >> 32);
  }
  std::size_t slot_of(Key key) const { return slot_of_hash(hash_key(key)); }
  std::size_t next(std::size_t i) const { return i + 1 == slots_.size() ? 0 : i + 1; }
  // Every recent answer becomes stale.
  void changed() { generation_ = next_generation(); }
  void place(Key key, NodeId node) {
    std::size_t i = slot_of(key);
    while (slots_[i].key != 0 && slots_[i].key != key) i = next(i);
    if (slots_[i].key == 0) ++size_;
    slots_[i] = Slot{key, node};
  }
  void rehash(std::size_t capacity) {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(capacity, Slot{});
    size_ = 0;
    for (const Slot& s : old)
      if (s.key != 0) place(s.key, s.node);
  }

  std::vector<Slot> slots_;
  std::size_t size_ = 0;
  // The answers of recent look-ups (absent cells too), valid while the table is unchanged: one neighbour
  // search looks up the same few cells several times as its box grows, and the operations of one
  // update lie close together. With millions of cells the table is far larger than the caches, and a
  // look-up there costs a cache and TLB miss. Direct-mapped by the top bits of the hash (the slot index
  // uses the low ones). One table per thread and key type, shared by all maps (entries name their
  // table's generation): the operations of a batch look up one map on several threads at once.
  static constexpr int kRecentBits = 8;
  struct RecentEntry {
    Key key = 0;
    NodeId node = kNoNode;
    std::uint64_t generation = 0;
  };
  using RecentTable = std::array<RecentEntry, std::size_t(1) << kRecentBits>;
  static RecentTable& recent_table() {
    static thread_local RecentTable table{};
    return table;
  }
  std::uint64_t generation_ = next_generation();  // new at every change; entries of older ones are stale
};

}  // namespace detail

class CellMap {
 public:
  template <int D>
  NodeId find(int level, const std::array<std::uint64_t, D>& coords) const {
    if (level <= kCompactLevels<D>) return compact_.find(compact_cell_key<D>(level, coords));
    return deep_.find(make_cell_key<D>(level, coords));
  }
  template <int D>
  void insert(int level, const std::array<std::uint64_t, D>& coords, NodeId node) {
    if (level <= kCompactLevels<D>)
      compact_.insert(compact_cell_key<D>(level, coords), node);
    else
      deep_.insert(make_cell_key<D>(level, coords), node);
  }
  template <int D>
  void prefetch(int level, const std::array<std::uint64_t, D>& coords) const {
    if (level <= kCompactLevels<D>)
      compact_.prefetch(compact_cell_key<D>(level, coords));
    else
      deep_.prefetch(make_cell_key<D>(level, coords));
  }
  template <int D>
  void erase(int level, const std::array<std::uint64_t, D>& coords) {
    if (level <= kCompactLevels<D>)
      compact_.erase(compact_cell_key<D>(level, coords));
    else
      deep_.erase(make_cell_key<D>(level, coords));
  }

  // Room for that many cells of levels up to kCompactLevels<D> and deeper ones, and a sixteenth more
  // when `spare` (a tree that edits will split further).
  void reserve(std::size_t compact_cells, std::size_t deep_cells, bool spare) {
    compact_.reserve(compact_cells, spare ? compact_cells / 16 : 0);
    deep_.reserve(deep_cells, spare ? deep_cells / 16 : 0);
  }
  void clear() {
    compact_.clear(kInitialCapacity);
    deep_.clear(kInitialDeepCapacity);
  }
  std::size_t size() const { return compact_.size() + deep_.size(); }
  std::size_t memory_bytes() const { return compact_.memory_bytes() + deep_.memory_bytes(); }

 private:
  static constexpr std::size_t kInitialCapacity = 64;
  static constexpr std::size_t kInitialDeepCapacity = 4;
  detail::CellTable<std::uint64_t> compact_{kInitialCapacity};
  detail::CellTable<CellKey> deep_{kInitialDeepCapacity};
};

}  // namespace shoremesh::engine
