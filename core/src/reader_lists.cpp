#include "shoremesh/engine/reader_lists.hpp"

#include <algorithm>
#include <bit>
#include <stdexcept>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

namespace shoremesh::engine {

namespace {
// Where id x is in ids (ids.size() if absent), eight entries per step: the reader lists of coarse
// squares hold hundreds of operations, and undo looks one up in each square its operation read
// (std::find there was 4 % of a 2D update's instructions).
std::size_t position_of(std::span<const std::uint32_t> ids, std::uint32_t x) {
  std::size_t i = 0;
#ifdef __SSE2__
  const __m128i key = _mm_set1_epi32(int(x));
  for (; i + 8 <= ids.size(); i += 8) {
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(ids.data() + i));
    const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(ids.data() + i + 4));
    if (_mm_movemask_epi8(_mm_or_si128(_mm_cmpeq_epi32(a, key), _mm_cmpeq_epi32(b, key))) != 0) break;
  }
#endif
  for (; i < ids.size(); ++i)
    if (ids[i] == x) return i;
  return ids.size();
}
}  // namespace

// Classes 1 to 8 hold 1 to 8 ids; then four per power of two: 10, 12, 14, 16, 20, 24, 28, 32, ... (a list
// laid out with little room wastes at most a quarter more to its class).
std::uint32_t ReaderLists::class_capacity(std::uint32_t c) {
  if (c <= 8) return c;
  const std::uint32_t m = c - 8;
  const std::uint32_t base = std::uint32_t(8) << (m / 4);
  return base + (m % 4) * (base / 4);
}

std::uint32_t ReaderLists::class_of(std::uint32_t length) {
  if (length <= 8) return length;
  const std::uint32_t k = std::uint32_t(std::bit_width(length - 1)) - 1;  // 2^k < length <= 2^(k+1), k >= 3
  const std::uint32_t base = std::uint32_t(1) << k, step = base / 4;
  return 8 + 4 * (k - 3) + (length - base + step - 1) / step;
}

void ReaderLists::grow_to(std::size_t nodes) {
  if (nodes > heads_.size()) heads_.resize(nodes);
}

std::uint32_t ReaderLists::take_block(std::uint32_t c) {
  if (c < free_heads_.size() && free_heads_[c] != kNoBlock) {
    const std::uint32_t begin = free_heads_[c];
    free_heads_[c] = entries_[begin];
    free_entries_ -= class_capacity(c);
    return begin;
  }
  const std::size_t begin = entries_.size();
  if (begin + class_capacity(c) > kNoBlock) throw std::length_error("reader lists: over 2^32 entries");
  entries_.resize(begin + class_capacity(c));
  return std::uint32_t(begin);
}

void ReaderLists::give_block(std::uint32_t begin, std::uint32_t c) {
  if (c == 0) return;
  if (free_heads_.size() <= c) free_heads_.resize(c + 1, kNoBlock);
  entries_[begin] = free_heads_[c];
  free_heads_[c] = begin;
  free_entries_ += class_capacity(c);
}

void ReaderLists::push(std::size_t node, std::uint32_t id) {
  Head& h = heads_[node];
  if (h.size == class_capacity(h.size_class)) {
    if (h.size == kMaxSize) throw std::length_error("reader lists: a list of over 2^25 operations");
    const std::uint32_t c = class_of(h.size + h.size / 4 + 1);
    const std::uint32_t begin = take_block(c);
    std::copy_n(entries_.begin() + h.begin, h.size, entries_.begin() + begin);
    give_block(h.begin, h.size_class);
    h.begin = begin;
    h.size_class = c & kClassMask;
  }
  entries_[h.begin + h.size] = id;
  h.size = h.size + 1;
}

bool ReaderLists::erase(std::size_t node, std::uint32_t id) {
  Head& h = heads_[node];
  const std::size_t at = position_of(list(node), id);
  if (at == h.size) return false;
  entries_[h.begin + at] = entries_[h.begin + h.size - 1];
  h.size = h.size - 1;
  return true;
}

void ReaderLists::clear(std::size_t node) {
  Head& h = heads_[node];
  give_block(h.begin, h.size_class);
  h = Head{};
}

void ReaderLists::clear() {
  heads_.clear();
  entries_.clear();
  free_heads_.clear();
  free_entries_ = 0;
}

std::size_t ReaderLists::live_block_entries() const {
  std::size_t live = 0;
  for (const Head& h : heads_) live += class_capacity(h.size_class);
  return live;
}

void ReaderLists::lay_out() {
  std::size_t room = 0;
  for (const Head& h : heads_)
    if (h.size > 0) room += class_capacity(class_of(h.size + h.size / 8 + 1));
  std::vector<std::uint32_t> entries;
  entries.reserve(room + room / 8 + 1024);
  for (Head& h : heads_) {
    const std::span<const std::uint32_t> ids = list(std::size_t(&h - heads_.data()));
    const std::uint32_t c = h.size > 0 ? class_of(h.size + h.size / 8 + 1) : 0;
    const auto begin = std::uint32_t(entries.size());
    entries.insert(entries.end(), ids.begin(), ids.end());
    entries.resize(begin + class_capacity(c));
    h.begin = begin;
    h.size_class = c & kClassMask;
  }
  entries_ = std::move(entries);
  free_heads_.clear();
  free_entries_ = 0;
  heads_.reserve(heads_.size() + heads_.size() / 8 + 1024);
}

}  // namespace shoremesh::engine
