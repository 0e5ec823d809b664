// The one error grammar of the executable: every failure is one line
// `skybake: error: <message>` on stderr and the exit code of core/error.hpp
// (with --json, also {"ok": false, "error", "exit_code"} on stdout). The
// messages for command-line mistakes CLI11 cannot word well (an unknown
// option or command, a missing input file) are made here, free of CLI11.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace skybake::cli {

// Prints the error line (and the JSON object when `json`); returns exit_code.
int print_error(const std::string& message, int exit_code, bool json);

// Runs a subcommand and turns what it throws into print_error: skybake
// errors with their own code (exit 5 ones worded "internal error: ..."),
// std::filesystem errors as file errors (4), anything else as internal (5).
int run_reporting_errors(const std::function<int()>& run, bool json);

// "<command>: unknown option '--bogus'" (no prefix for an empty command),
// with "(did you mean '--force'?)"
// for a near option or for a flag that was renamed (plan -d is -o, report
// --products is --only). `options` are the command's names, e.g. "--force", "-f".
std::string unknown_option_message(const std::string& command, const std::string& arg,
                                   const std::vector<std::string>& options);

// "unknown command 'bak' (did you mean 'bake'?)", or the list of commands.
std::string unknown_command_message(const std::string& arg,
                                    const std::vector<std::string>& commands);

// "no command given (commands: bake, validate, ...)".
std::string no_command_message(const std::vector<std::string>& commands);

// Preset entries (files, folders, glob patterns): a file or folder that does
// not exist is an IoError as above; a pattern that matches nothing is left
// to expand_catalog (a usage error). Returns the expanded, sorted presets.
std::vector<std::filesystem::path> expand_presets(const std::vector<std::string>& entries);

}  // namespace skybake::cli
