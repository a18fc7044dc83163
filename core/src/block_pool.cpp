#include "shoremesh/engine/block_pool.hpp"

#include <algorithm>
#include <bit>

namespace shoremesh::engine {

std::uint32_t BlockPool::block_size(std::uint32_t length) {
  return length <= kExactSizes ? length : std::bit_ceil(length);
}

// Classes 1 .. kExactSizes are the exact sizes; then one class per power of two.
std::size_t BlockPool::size_class(std::uint32_t block) {
  if (block <= kExactSizes) return block;
  return kExactSizes + std::size_t(std::countr_zero(block) - std::countr_zero(kExactSizes));
}

std::uint32_t BlockPool::allocate(std::span<const std::uint32_t> run) {
  const auto length = std::uint32_t(run.size());
  if (length == 0) return 0;
  const std::uint32_t block = block_size(length);
  const std::size_t c = size_class(block);
  std::uint32_t begin;
  if (c < free_heads_.size() && free_heads_[c] != kNoBlock) {
    begin = free_heads_[c];
    free_heads_[c] = entries_[begin];
    free_entries_ -= block;
  } else {
    begin = std::uint32_t(entries_.size());
    entries_.resize(entries_.size() + block);
  }
  std::copy(run.begin(), run.end(), entries_.begin() + begin);
  return begin;
}

void BlockPool::release(std::uint32_t begin, std::uint32_t size) {
  if (size == 0) return;
  const std::uint32_t block = block_size(size);
  const std::size_t c = size_class(block);
  if (free_heads_.size() <= c) free_heads_.resize(c + 1, kNoBlock);
  entries_[begin] = free_heads_[c];
  free_heads_[c] = begin;
  free_entries_ += block;
}

void BlockPool::clear() {
  entries_.clear();
  free_heads_.clear();
  free_entries_ = 0;
}

}  // namespace shoremesh::engine
