#include "core/fresh_pages.hpp"

#include <algorithm>
#include <cstdint>

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace skybake {

namespace {

// Writes every page of [a, b) (page-aligned) with the byte it holds: a
// write fault per page that is not yet writable in the MMU, nothing else.
// Where the kernel has made the pages writable already this costs a load
// and a store per 4 KB. Under a hypervisor that shadows the guest's page
// tables (the development VM), MADV_POPULATE_WRITE fills the guest's tables
// but each page's first write from the program still exits to the
// hypervisor, about 5 us a page (1.3 ms per MB); done here, those exits are
// split between the threads instead of falling on the zero fill's one
// (docs/decisions.md "Threads: a fresh texture's first write").
void touch_pages(uintptr_t a, uintptr_t b, uintptr_t page) {
  for (uintptr_t x = a; x < b; x += page) {
    volatile char* c = reinterpret_cast<volatile char*>(x);
    *c = *c;
  }
}

}  // namespace

void populate_pages(void* p, size_t bytes) {
#if defined(MADV_POPULATE_WRITE)
  const uintptr_t page = uintptr_t(sysconf(_SC_PAGESIZE));
  const uintptr_t begin = (uintptr_t(p) + page - 1) & ~(page - 1);
  const uintptr_t end = (uintptr_t(p) + bytes) & ~(page - 1);
  if (end <= begin) return;
  // 256 KB a chunk: a 1 MB buffer still splits between two threads.
  const uintptr_t chunk = 64 * page;
  const size_t chunks = size_t((end - begin + chunk - 1) / chunk);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks),
                    [&](const tbb::blocked_range<size_t>& r) {
                      const uintptr_t a = begin + r.begin() * chunk;
                      const uintptr_t b = std::min<uintptr_t>(end, begin + r.end() * chunk);
                      // A failure (EINVAL before Linux 5.14, ENOMEM) leaves the pages to
                      // fault on first write: slower, the same bytes.
                      (void)madvise(reinterpret_cast<void*>(a), b - a, MADV_POPULATE_WRITE);
                      touch_pages(a, b, page);
                    });
#else
  (void)p;
  (void)bytes;
#endif
}

void keep_freed_memory() {
#if defined(__GLIBC__)
  // glibc's ceiling for the threshold on 64-bit (DEFAULT_MMAP_THRESHOLD_MAX);
  // setting it also stops the threshold moving.
  (void)mallopt(M_MMAP_THRESHOLD, 32 << 20);
  (void)mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace skybake
