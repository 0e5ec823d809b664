// Faulting in the pages of a fresh allocation on every thread.
//
// A large buffer from malloc is fresh anonymous memory: its first write costs
// a page fault per 4 KB page, in which the kernel zeroes the page and charges
// it to the process. For a 32 MB volume that is 8192 faults, 15-20 ms of CPU
// measured, more than zeroing the memory itself; done by
// the thread that allocates, it is a serial prefix of every parallel bake
// (docs/decisions/fresh-pages.md).
#pragma once

#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

namespace skybake {

// Asks the kernel to fault in every whole page of [p, p + bytes) for
// writing, split into chunks run by TBB's threads (madvise
// MADV_POPULATE_WRITE, Linux 5.14). It writes nothing a program can see: a
// fresh page still reads as zeros and a present one keeps its contents.
// Where the call is not available or fails, it does nothing, and the pages
// fault when first written, as before.
void populate_pages(void* p, size_t bytes);

// Below this size a buffer is zeroed by the allocating thread alone: the
// faults cost less than waking the workers.
constexpr size_t kPopulateMinBytes = size_t(1) << 20;

// Zeroed memory for a buffer of `bytes`, to be given back with
// free_fresh_pages. From kPopulateMinBytes up it is its own anonymous
// mapping of whole 2 MB blocks on a 2 MB boundary, advised for transparent
// huge pages (one fault each instead of 512, see fresh_pages.cpp) and
// populated on every thread (populate_pages): the kernel's zero fill of
// each page is the buffer's, split between the threads. Below it, calloc.
// Throws std::bad_alloc.
void* allocate_fresh_pages(size_t bytes);
void free_fresh_pages(void* p, size_t bytes) noexcept;

// The allocator of a texture's texels: allocate_fresh_pages for every
// buffer (the mapping or calloc is the size's choice, the same on
// allocation and release). Its memory is zeroed, so a value-initialized
// element (`TexelVector(n)`, `resize(n)`) is left as the memory holds it,
// 0.0f, instead of by a memset on the constructing thread: for a 32 MB
// volume that memset was about a tenth of a one-thread bake, all of it
// serial (docs/decisions/fresh-pages.md). The
// one way to see the difference: a vector shrunk and then grown again
// within its capacity keeps the old values in the regrown elements, so
// grow a TexelVector with resize(n, 0.0f) or assign.
template <class T>
struct FreshPagesAllocator {
  static_assert(std::is_trivially_default_constructible_v<T>,
                "zeroed memory is a value-initialized T only for trivial types");
  using value_type = T;
  FreshPagesAllocator() = default;
  template <class U>
  FreshPagesAllocator(const FreshPagesAllocator<U>&) noexcept {}
  T* allocate(size_t n) {
    if (n > size_t(-1) / sizeof(T)) throw std::bad_alloc();
    return static_cast<T*>(allocate_fresh_pages(n * sizeof(T)));
  }
  void deallocate(T* p, size_t n) noexcept { free_fresh_pages(p, n * sizeof(T)); }
  // Value-initialization: the memory is zero already (see above).
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  bool operator==(const FreshPagesAllocator<U>&) const noexcept {
    return true;
  }
  template <class U>
  bool operator!=(const FreshPagesAllocator<U>&) const noexcept {
    return false;
  }
};

// Keeps the memory the process frees for its own later allocations. By
// default glibc hands a freed buffer of 128 KB and up (its threshold moves
// up to the largest freed, at most 32 MB) and the heap's free top back to
// the kernel, so the next buffer is fresh pages again; on a virtual machine
// a fresh page's first write costs several microseconds (about 2 ms of CPU
// per MB, bench/noise_set_bench.sh). Buffers under 32 MB then come from
// the heap and freed heap memory is kept (a texture's texels from 1 MB up
// excepted: FreshPagesAllocator maps and unmaps its own, in huge pages at
// one fault per 2 MB): a process's resident memory stays
// at its peak until it exits (short bake processes). Called once, first
// thing in main (glibc's mallopt is not for concurrent use).
void keep_freed_memory();

}  // namespace skybake
