#pragma once
// Between the stages of a one-shot run: hand the pages the allocator keeps for reuse back to the system.
namespace shoremesh::tool {

// jemalloc (allocator.cpp) keeps freed pages resident for about ten seconds (its decay) so that a later
// allocation reuses them without a page fault. A one-shot `mesh` frees its reading's temporaries (about
// half the memory the reading touched) and then builds the engine, which makes different sizes of block:
// the kept pages stayed resident beside the engine's and raised the whole run's peak (bench/RESULTS.md,
// "The one-shot pipeline's peak"). Does nothing without jemalloc (the sanitizer builds).
void release_free_memory();

}  // namespace shoremesh::tool
