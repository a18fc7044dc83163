#pragma once
// Per quadtree node, the operations that read it: every node's list is one block of 32-bit ids in one
// array, reached through an 8-byte head (where the block begins, how many ids it holds, its size class).
// A std::vector per node cost a 24-byte head, a heap allocation of at least 32 bytes even for the many
// empty lists, and room reserved in each: 129 bytes per output vertex at 2D n = 1e5, against the ids'
// 30 (bench/RESULTS.md).
//
// A list that fills its block moves to a block of a size class about a quarter larger (classes: 1 to 8,
// then four per power of two); a block given back goes on a free list of its class, which the next list of that
// class takes, so the array follows the live lists with no compaction pass (as BlockPool does for runs).
// lay_out() writes the lists again in node order, each with room to grow: marking and undo walk the
// lists of neighbouring nodes together, and an update mostly adds to a list what it took from it.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace shoremesh::engine {

class ReaderLists {
 public:
  std::size_t node_count() const { return heads_.size(); }
  // Heads for nodes [0, nodes): new nodes get empty lists (never shrinks).
  void grow_to(std::size_t nodes);
  std::span<const std::uint32_t> list(std::size_t node) const {
    const Head& h = heads_[node];
    return {entries_.data() + h.begin, h.size};
  }
  void push(std::size_t node, std::uint32_t id);
  // Takes id out of the node's list (the last id takes its place); false if it was not there.
  bool erase(std::size_t node, std::uint32_t id);
  // Empties the node's list and gives its block back.
  void clear(std::size_t node);
  // Every list emptied, every head gone.
  void clear();
  // Renames every id of every list: id = f(id).
  template <class F>
  void rename(F&& f) {
    for (const Head& h : heads_)
      for (std::uint32_t k = h.begin; k < h.begin + h.size; ++k) entries_[k] = f(entries_[k]);
  }
  // Writes the lists again in node order, each in a block with room for an eighth more (at least one
  // id), and room for an eighth more nodes and ids: a build's lists are written in the order of its
  // operations, scattered, and a block or array grown in the middle of an update copies itself there.
  void lay_out();

  // Ids in blocks (live or free), and in free blocks: the blocks of the lists and the free ones make up
  // the array (check_valid).
  std::size_t size() const { return entries_.size(); }
  std::size_t free_entries() const { return free_entries_; }
  std::size_t live_block_entries() const;
  std::size_t memory_bytes() const {
    return heads_.capacity() * sizeof(Head) + entries_.capacity() * sizeof(std::uint32_t) +
           free_heads_.capacity() * sizeof(std::uint32_t);
  }

  // The capacity of size class c (0: no block), and the least class holding `length` ids.
  static std::uint32_t class_capacity(std::uint32_t c);
  static std::uint32_t class_of(std::uint32_t length);

 private:
  static constexpr std::uint32_t kSizeBits = 25;
  static constexpr std::uint32_t kClassMask = (std::uint32_t(1) << (32 - kSizeBits)) - 1;
  static constexpr std::uint32_t kMaxSize = (std::uint32_t(1) << kSizeBits) - 1;
  static constexpr std::uint32_t kNoBlock = UINT32_MAX;
  struct Head {
    std::uint32_t begin = 0;
    std::uint32_t size : kSizeBits = 0;
    std::uint32_t size_class : 32 - kSizeBits = 0;
  };
  static_assert(sizeof(Head) == 8);
  // A block of class c, from its free list or the array's end.
  std::uint32_t take_block(std::uint32_t c);
  void give_block(std::uint32_t begin, std::uint32_t c);

  std::vector<Head> heads_;
  std::vector<std::uint32_t> entries_;     // a free block keeps the next free block of its class in its first id
  std::vector<std::uint32_t> free_heads_;  // per size class: the first free block, or kNoBlock
  std::size_t free_entries_ = 0;
};

}  // namespace shoremesh::engine
