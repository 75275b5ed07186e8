// The allocator's policy (malloc_conf.cpp, linked into every wisp program that renders or solves).
#pragma once

namespace wisp::cli {

// Returns the pages of every freed allocation to the system now, instead of over jemalloc's decay
// (10 s, malloc_conf.cpp). For a program whose next step allocates afresh what the freed memory
// cannot serve: the peak is then what is in use, not that plus what was. A no-op without jemalloc.
void return_free_pages();

}  // namespace wisp::cli
