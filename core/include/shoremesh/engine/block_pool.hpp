#pragma once
// Short runs of 32-bit ids in one array: each operation's children and the squares it read. An update
// takes back the runs of the operations it undoes and writes new ones for those it runs again. A run
// given back leaves its block on a free list of its size class, and the next run of that class takes
// it, so the array follows the live runs with no compaction pass. (The engine used to append every
// new run and compact the array once the dead entries outnumbered the live ones: a pause of 38 to 45
// ms every 7,000 changes or so at 2D n = 1e5, and of half a second every 65,000 at n = 1e6,
// bench/RESULTS.md.)
//
// Size classes: a run of up to kExactSizes entries gets a block of exactly its size (an operation reads
// a few squares and asks for a few fills), a longer one the next power of two. A block's size follows
// from its run's length, so the runs need not store it.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace shoremesh::engine {

class BlockPool {
 public:
  // Copies run into a block; returns where it begins (the run is [begin, begin + run.size())).
  std::uint32_t allocate(std::span<const std::uint32_t> run);
  // Gives back the block of the run [begin, begin + size) (size 0: nothing to give).
  void release(std::uint32_t begin, std::uint32_t size);

  std::uint32_t operator[](std::size_t k) const { return entries_[k]; }
  std::uint32_t& operator[](std::size_t k) { return entries_[k]; }
  std::span<const std::uint32_t> run(std::uint32_t begin, std::uint32_t end) const {
    return {entries_.data() + begin, entries_.data() + end};
  }

  // Room for this many entries in all, so that runs written later do not copy the array.
  void reserve(std::size_t entries) { entries_.reserve(entries); }
  void clear();
  // Entries in blocks, live or free; those in free blocks.
  std::size_t size() const { return entries_.size(); }
  std::size_t free_entries() const { return free_entries_; }
  std::size_t memory_bytes() const {
    return entries_.capacity() * sizeof(std::uint32_t) + free_heads_.capacity() * sizeof(std::uint32_t);
  }

  // The block a run of this length takes.
  static std::uint32_t block_size(std::uint32_t length);

 private:
  static constexpr std::uint32_t kExactSizes = 32;
  static constexpr std::uint32_t kNoBlock = UINT32_MAX;
  static std::size_t size_class(std::uint32_t block);

  std::vector<std::uint32_t> entries_;  // a free block keeps the next free block of its class in its first entry
  std::vector<std::uint32_t> free_heads_;  // per size class: the first free block, or kNoBlock
  std::size_t free_entries_ = 0;
};

}  // namespace shoremesh::engine
