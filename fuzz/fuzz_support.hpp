// Shared by the libFuzzer harnesses: the input as a file (the readers take
// paths), and the rule every harness checks: hostile input may only end in a
// user-facing error (exit 1 to 4), never in an internal one (exit 5), an
// exception of another kind, a crash or a sanitizer report.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/error.hpp"

namespace skybake::fuzz {

// A folder of this process's own (made once, under $TMPDIR or /tmp).
const std::filesystem::path& work_dir();

// Writes the input to work_dir()/name and returns its path.
std::string write_input(const uint8_t* data, size_t size, const std::string& name);

// Runs `read`: an Error of exit code 5 aborts (a finding), any other Error is
// the expected refusal, and any other exception propagates (a finding too).
template <typename F>
void expect_no_internal_error(F&& read) {
  try {
    read();
  } catch (const Error& e) {
    if (e.exit_code() == kExitInternal) {
      std::fprintf(stderr, "internal error on hostile input: %s\n", e.what());
      std::abort();
    }
  }
}

}  // namespace skybake::fuzz
