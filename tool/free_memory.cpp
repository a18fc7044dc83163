#include "free_memory.hpp"

#include <cstddef>

// jemalloc's control interface, weak: linked only where allocator.cpp brings jemalloc in.
extern "C" int mallctl(const char* name, void* oldp, std::size_t* oldlenp, void* newp, std::size_t newlen)
    __attribute__((weak));

namespace shoremesh::tool {

void release_free_memory() {
  // "arena.<MALLCTL_ARENAS_ALL>.purge": every arena's unused dirty pages, at once.
  if (mallctl) mallctl("arena.4096.purge", nullptr, nullptr, nullptr, 0);
}

}  // namespace shoremesh::tool
