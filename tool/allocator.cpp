// The allocator of shoremesh's executables: the tool and the benchmarks link jemalloc (see
// tool/CMakeLists.txt), set here to back its memory with transparent huge pages.
//
// Why: an update reads the engine's memory at scattered places (quadtree leaves, operations, reader
// lists of one neighbourhood lie far apart in the gigabytes of a large input), and with 4 KiB pages
// nearly every such read misses the TLB too. Debian's kernels give huge pages only to memory that asks
// for them (THP "madvise"), and glibc's malloc does not ask. bench/RESULTS.md has the measurements
// (2D, n = 1e6: the median update about a third faster).
extern "C" {
// jemalloc reads this documented global at start-up; the MALLOC_CONF variable still overrides it.
extern const char* malloc_conf;
const char* malloc_conf = "thp:always,metadata_thp:auto";
}
