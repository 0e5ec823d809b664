#include "core/fresh_pages.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

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
// (docs/decisions/fresh-pages.md).
void touch_pages(uintptr_t a, uintptr_t b, uintptr_t page) {
  for (uintptr_t x = a; x < b; x += page) {
    volatile char* c = reinterpret_cast<volatile char*>(x);
    *c = *c;
  }
}

// The x86-64 and AArch64 (4 KB granule) size of a transparent huge page.
constexpr uintptr_t kHugePage = uintptr_t(2) << 20;

// Asks for transparent huge pages on the whole 2 MB blocks of [a, b), and
// says whether there is at least one. A huge page is one fault and one
// mapping where 4 KB pages are 512: the kernel zeroes the same bytes, but
// the faults, and under a hypervisor that shadows the guest's page tables
// the exit on each page's first write (about 5 us a page on the development
// VM), are 512 times fewer (docs/decisions/fresh-pages.md). Where THP is off ("never") the call changes nothing;
// where it is "always" the pages were to be huge anyway.
bool advise_huge_pages(uintptr_t a, uintptr_t b) {
#if defined(MADV_HUGEPAGE)
  const uintptr_t ha = (a + kHugePage - 1) & ~(kHugePage - 1);
  const uintptr_t hb = b & ~(kHugePage - 1);
  if (hb <= ha) return false;
  return madvise(reinterpret_cast<void*>(ha), hb - ha, MADV_HUGEPAGE) == 0;
#else
  (void)a;
  (void)b;
  return false;
#endif
}

}  // namespace

void populate_pages(void* p, size_t bytes) {
#if defined(MADV_POPULATE_WRITE)
  const uintptr_t page = uintptr_t(sysconf(_SC_PAGESIZE));
  const uintptr_t begin = (uintptr_t(p) + page - 1) & ~(page - 1);
  const uintptr_t end = (uintptr_t(p) + bytes) & ~(page - 1);
  if (end <= begin) return;
  // 256 KB a chunk: a 1 MB buffer still splits between two threads. With
  // huge pages a chunk is one of them, on their boundaries, as a fault fills
  // a whole one.
  const uintptr_t chunk = advise_huge_pages(begin, end) ? kHugePage : 64 * page;
  const uintptr_t base = begin & ~(chunk - 1);
  const size_t chunks = size_t((end - base + chunk - 1) / chunk);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks),
                    [&](const tbb::blocked_range<size_t>& r) {
                      const uintptr_t a = std::max<uintptr_t>(begin, base + r.begin() * chunk);
                      const uintptr_t b = std::min<uintptr_t>(end, base + r.end() * chunk);
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

void* allocate_fresh_pages(size_t bytes) {
  if (bytes < kPopulateMinBytes) {
    void* p = std::calloc(bytes > 0 ? bytes : 1, 1);
    if (p == nullptr) throw std::bad_alloc();
    return p;
  }
  // Whole huge pages: a buffer's last partial 2 MB would otherwise be 4 KB
  // pages, up to 511 faults (and exits) for at most 2 MB - 4 KB unused. A
  // mapping of one block more than that is trimmed to the 2 MB boundary;
  // its pages are fresh, so zero without a memset.
  if (bytes > size_t(-1) - 2 * kHugePage) throw std::bad_alloc();
  const size_t whole = (bytes + kHugePage - 1) & ~(kHugePage - 1);
  const size_t span = whole + kHugePage;
  void* m = mmap(nullptr, span, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (m == MAP_FAILED) throw std::bad_alloc();
  const uintptr_t start = uintptr_t(m);
  const uintptr_t a = (start + kHugePage - 1) & ~(kHugePage - 1);
  if (a > start) munmap(m, a - start);
  if (start + span > a + whole) munmap(reinterpret_cast<void*>(a + whole), start + span - a - whole);
  populate_pages(reinterpret_cast<void*>(a), whole);
  return reinterpret_cast<void*>(a);
}

void free_fresh_pages(void* p, size_t bytes) noexcept {
  if (bytes < kPopulateMinBytes)
    std::free(p);
  else
    munmap(p, (bytes + kHugePage - 1) & ~(kHugePage - 1));
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
