#include "cli/errors.hpp"

#include <cstdio>
#include <iostream>
#include <map>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/suggest.hpp"
#include "farm/catalog.hpp"

namespace fs = std::filesystem;

namespace skybake::cli {

namespace {

// Flags that were renamed when the commands got one grammar: the old name is
// an unknown option whose suggestion is the new one.
std::string renamed_flag(const std::string& command, const std::string& flag) {
  static const std::map<std::pair<std::string, std::string>, std::string> renamed = {
      {{"plan", "-d"}, "-o"},
      {{"plan", "--out-dir"}, "--out"},
      {{"plan", "--output"}, "--emit-file"},
      {{"report", "--products"}, "--only"}};
  const auto it = renamed.find({command, flag});
  return it == renamed.end() ? "" : it->second;
}

bool is_pattern(const std::string& entry) {
  return entry.find_first_of("*?[") != std::string::npos;
}

}  // namespace

int print_error(const std::string& message, int exit_code, bool json) {
  std::fprintf(stderr, "skybake: error: %s\n", message.c_str());
  if (json)
    std::cout << nlohmann::json{{"ok", false}, {"error", message}, {"exit_code", exit_code}}.dump(2)
              << "\n";
  return exit_code;
}

int run_reporting_errors(const std::function<int()>& run, bool json) {
  try {
    return run();
  } catch (const Error& e) {
    const bool internal = e.exit_code() == kExitInternal;
    return print_error(internal ? std::string("internal error: ") + e.what() : e.what(),
                       e.exit_code(), json);
  } catch (const fs::filesystem_error& e) {
    return print_error(e.what(), kExitIo, json);
  } catch (const std::exception& e) {
    return print_error(std::string("internal error: ") + e.what(), kExitInternal, json);
  }
}

std::string unknown_option_message(const std::string& command, const std::string& arg,
                                   const std::vector<std::string>& options) {
  const std::string flag = arg.substr(0, arg.find('='));
  const std::string renamed = renamed_flag(command, flag);
  const std::string hint =
      renamed.empty() ? did_you_mean(flag, options) : " (did you mean '" + renamed + "'?)";
  return fmt::format("{}unknown option '{}'{}", command.empty() ? "" : command + ": ", flag, hint);
}

std::string unknown_command_message(const std::string& arg,
                                    const std::vector<std::string>& commands) {
  const std::string hint = did_you_mean(arg, commands);
  return fmt::format("unknown command '{}'{}", arg,
                     hint.empty() ? fmt::format(" (commands: {})", fmt::join(commands, ", ")) : hint);
}

std::string no_command_message(const std::vector<std::string>& commands) {
  return fmt::format("no command given (commands: {})", fmt::join(commands, ", "));
}

std::vector<fs::path> expand_presets(const std::vector<std::string>& entries) {
  for (const std::string& entry : entries)
    if (!is_pattern(entry) && !fs::exists(entry)) throw IoError(entry + ": no such file");
  return expand_catalog(entries);
}

}  // namespace skybake::cli
