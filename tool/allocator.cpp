// The allocator of shoremesh's executables: the tool and the benchmarks link jemalloc (see
// tool/CMakeLists.txt), set here to back its memory with transparent huge pages.
//
// Why: the engine keeps millions of small blocks (each quadtree leaf's vertices, each square's list of
// readers) and reads them at scattered places. Debian's kernels give huge pages only to memory that
// asks for them (THP "madvise"), and glibc's malloc does not ask. Measured (bench/RESULTS.md, 2D,
// n = 3e5): StableWS from scratch 26 % faster than with glibc's malloc (jemalloc alone 17 %, its huge
// pages the rest); the latency of one update moved less than this machine's noise. The cost: peak
// memory +34 % at n = 1e4, +13 % at 1e5, +1.7 % at 1e6 (MALLOC_CONF=thp:never turns them off).
//
// One arena for all threads (jemalloc's default: four per core, a thread's blocks freed into its own):
// the engine's batches run on every thread, then the writing and the quality summary run beside each
// other, and each arena kept its own freed pages and part-used huge pages for its threads alone. Lake
// Superior on two threads peaked at 274-278 MiB with the default, 249-252 with one arena, in the same
// CPU time (bench/RESULTS.md); the threads' caches (tcache) keep most allocations off the arena's lock.
extern "C" {
// jemalloc reads this documented global at start-up; the MALLOC_CONF variable still overrides it.
extern const char* malloc_conf;
const char* malloc_conf = "thp:always,metadata_thp:auto,narenas:1";
}
