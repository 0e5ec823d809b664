// Faulting in the pages of a fresh allocation on every thread.
//
// A large buffer from malloc is fresh anonymous memory: its first write costs
// a page fault per 4 KB page, in which the kernel zeroes the page and charges
// it to the process. For a 32 MB volume that is 8192 faults, 15-20 ms of CPU
// on the development machine, more than zeroing the memory itself; done by
// the thread that allocates, it is a serial prefix of every parallel bake
// (docs/decisions.md "Threads: the serial parts of a bake").
#pragma once

#include <cstddef>

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

// Keeps the memory the process frees for its own later allocations. By
// default glibc hands a freed buffer of 128 KB and up (its threshold moves
// up to the largest freed, at most 32 MB) and the heap's free top back to
// the kernel, so the next buffer is fresh pages again; on a virtual machine
// a fresh page's first write costs several microseconds (about 2 ms of CPU
// per MB on the shared development machine, docs/decisions.md "The
// cloud-noise set's CPU, fourth pass"). Buffers under 32 MB then come from
// the heap and freed heap memory is kept: a process's resident memory stays
// at its peak until it exits (short bake processes). Called once, first
// thing in main (glibc's mallopt is not for concurrent use).
void keep_freed_memory();

}  // namespace skybake
