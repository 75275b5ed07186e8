// jemalloc's options for every wisp program (linked into each wisp-<command>, wisp-inspect and
// wisp-bench). jemalloc is linked with the arrangement (vector/CMakeLists.txt) and reads this
// symbol at start-up; MALLOC_CONF in the environment still overrides it.
//
// Why these (docs/performance.md, "Page faults and huge pages"): a 1024^2 frame allocates and frees
// tens of MB (the arrangement, the image planes, Cairo's surfaces), and on a virtual machine every
// page that comes back to the process costs a page fault of about 10 us. With pages returned a
// quarter second after they were freed, `wisp render` of the default scene took 1.4 million faults
// and 40 % of its CPU in them. Freed pages are now kept for 10 s, long enough to be reused by the
// next frames (at 3 s, 48 frames of the default scene at 512^2 took 16 000 faults against 13 500,
// and a whole render at 1024^2 6 % more CPU: docs/performance.md, "The tenth session"), and large
// extents are backed by transparent huge pages (2 MB: a 512th of the faults and of the TLB
// misses; the solver's passes over 12 MB planes run at half the user time in `wisp diffuse`). One
// arena for all threads keeps one pool of freed pages rather than one a thread, which holds the
// peak at 1024^2 with two threads at 242-259 MB (target 300). A background thread returns the pages
// once they have not been used for that long.
#include "apps/cli/malloc_conf.hpp"

#include <cstddef>

extern "C" {
extern const char* malloc_conf;
const char* malloc_conf =
    "background_thread:true,narenas:1,dirty_decay_ms:10000,muzzy_decay_ms:0,thp:always,"
    "metadata_thp:always";
}

// jemalloc's control interface, weak: the sanitizer and fuzzing builds link no jemalloc, and
// there it is null.
extern "C" int mallctl(const char* name, void* old, std::size_t* old_size, void* value,
                       std::size_t value_size) __attribute__((weak));

namespace wisp::cli {

void return_free_pages() {
  if (mallctl) mallctl("arena.4096.purge", nullptr, nullptr, nullptr, 0);  // MALLCTL_ARENAS_ALL
}

}  // namespace wisp::cli
