// Help text describes what the tool does: every output format the writer
// knows is in the top-level help, every format read_texture_file reads in
// the help of `info` and `check-tiling`, and every registered product in
// the "Products (--only):" list of each command that takes --only. The
// lists come from the code (output_formats, texture_file_formats,
// product_registry), so a new format or product without help fails here.
#include <algorithm>
#include <cctype>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/texture_file.hpp"
#include "pipeline/output_writer.hpp"
#include "pipeline/product.hpp"
#include "support/run.hpp"

namespace skybake {
namespace {

std::string help_of(const std::vector<std::string>& args) {
  const test::RunResult r = test::run_skybake(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.out;
}

std::string upper(const std::string& s) {
  std::string out;
  for (char c : s) out += char(std::toupper((unsigned char)c));
  return out;
}

// The line of `text` that starts with `prefix` after leading blanks, or "".
std::string line_with(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const size_t start = line.find_first_not_of(' ');
    if (start != std::string::npos && line.compare(start, prefix.size(), prefix) == 0) return line;
  }
  return "";
}

// The words of the "Products (--only):" block: its line and the lines
// below it up to the next blank line.
std::set<std::string> only_products(const std::string& help) {
  const size_t at = help.find("Products (--only):");
  if (at == std::string::npos) return {};
  const size_t end = help.find("\n\n", at);
  std::istringstream in(help.substr(at + 18, end == std::string::npos ? std::string::npos : end - at - 18));
  std::set<std::string> words;
  for (std::string w; in >> w;) words.insert(w);
  return words;
}

TEST(HelpText, TopLevelHelpNamesEveryOutputFormatAndProduct) {
  const std::string help = help_of({"--help"});
  const std::string intro = line_with(help, "from JSON scene presets into");
  ASSERT_FALSE(intro.empty()) << help;
  for (const std::string& f : output_formats())
    EXPECT_NE(intro.find(upper(f)), std::string::npos) << f << " missing from: " << intro;
  for (const ProductInfo& p : product_registry())
    EXPECT_FALSE(line_with(help, p.name + " ").empty()) << p.name << " missing from --help";
}

TEST(HelpText, OutputFormatsAreExactlyThoseTheProductsAllow) {
  std::set<std::string> allowed;
  for (const ProductInfo& p : product_registry())
    allowed.insert(p.allowed_formats.begin(), p.allowed_formats.end());
  EXPECT_EQ(allowed, std::set<std::string>(output_formats().begin(), output_formats().end()));
}

TEST(HelpText, InfoAndCheckTilingNameEveryFormatTheyRead) {
  const std::string top = help_of({"--help"});
  for (const char* command : {"info", "check-tiling"}) {
    SCOPED_TRACE(command);
    const std::string own = help_of({command, "--help"});
    const std::string summary = line_with(top, std::string(command) + " ");
    for (const std::string& f : texture_file_formats()) {
      EXPECT_NE(own.find(upper(f)), std::string::npos) << f << " missing from: " << own;
      EXPECT_NE(summary.find(upper(f)), std::string::npos) << f << " missing from: " << summary;
    }
  }
}

TEST(HelpText, EveryCommandWithOnlyListsEveryProduct) {
  std::set<std::string> products;
  for (const ProductInfo& p : product_registry()) products.insert(p.name);
  for (const char* command : {"bake", "plan", "report"}) {
    SCOPED_TRACE(command);
    const std::string help = help_of({command, "--help"});
    ASSERT_NE(help.find("--only"), std::string::npos);
    EXPECT_EQ(only_products(help), products) << help;
  }
}

}  // namespace
}  // namespace skybake
