// Test support: runs a piece of code in a child process whose address space
// is capped, so a test can tell "refused before allocating" from "allocated
// and then refused" without timing anything.
#pragma once

#include <cstddef>
#include <functional>

namespace skybake::test {

// Forks; the child caps its address space at what it maps now plus
// `headroom` bytes (RLIMIT_AS), runs `body` and exits with its result (99
// when an allocation fails, 98 on any other exception). Returns the child's
// exit code, or -1 when it died of a signal.
int run_with_memory_headroom(size_t headroom, const std::function<int()>& body);

}  // namespace skybake::test
