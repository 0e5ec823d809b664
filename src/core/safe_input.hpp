// Reading files that a user or another machine may have made hostile: JSON
// documents (presets, catalog entries, manifest.json) are read only from
// regular files of bounded size, and their nesting is bounded before any
// recursive parser, converter or destructor sees them (a few thousand levels
// exhaust the stack of rapidjson's parser and of every recursive walk of the
// tree). The limits and their reasons are in docs/decisions/hostile-json.md, "Hostile
// inputs".
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace skybake {

// Deepest nesting of arrays and objects in any JSON file skybake reads. The
// deepest document skybake itself writes or ships has fewer than 10 levels.
constexpr int kMaxJsonDepth = 128;

// Largest JSON file skybake reads (a manifest of thousands of outputs is a
// few MB).
constexpr std::uintmax_t kMaxJsonFileBytes = std::uintmax_t(64) << 20;

enum class ReadStatus {
  ok,       // `text` holds the whole file
  missing,  // no such file (or a path component is not a folder)
  refused,  // not a regular file, too large, or unreadable: `why` says which
};

struct FileText {
  ReadStatus status = ReadStatus::ok;
  std::string text;
  std::string why;  // the rule, for messages: "is a directory, expected a regular file"
};

// Reads a whole regular file of at most `max_bytes`. Checks the type and
// size with stat before opening, opens with O_NONBLOCK (a FIFO swapped in
// between cannot block), checks the opened descriptor again with fstat, and
// never reads more than max_bytes + 1 bytes (a file that grows while being
// read is refused). Never throws for anything about the file itself.
FileText read_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes);

// nullopt when no array or object in `text` is nested deeper than
// `max_depth`; else the rule, naming the line and column where the limit is
// crossed: "nests arrays and objects deeper than the limit of 128 levels
// (line 1, column 129)". A linear scan that skips strings (escapes included) and needs no
// valid JSON: it runs before the parser.
std::optional<std::string> json_nesting_problem(std::string_view text,
                                                int max_depth = kMaxJsonDepth);

}  // namespace skybake
