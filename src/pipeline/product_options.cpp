#include "pipeline/product_options.hpp"

#include <fmt/format.h>

namespace skybake {

int option_int(const OutputSpec& spec, const std::string& key, int fallback) {
  auto it = spec.options.find(key);
  return it != spec.options.end() && it->is_number() ? it->get<int>() : fallback;
}
double option_double(const OutputSpec& spec, const std::string& key, double fallback) {
  auto it = spec.options.find(key);
  return it != spec.options.end() && it->is_number() ? it->get<double>() : fallback;
}
std::string option_string(const OutputSpec& spec, const std::string& key,
                          const std::string& fallback) {
  auto it = spec.options.find(key);
  return it != spec.options.end() && it->is_string() ? it->get<std::string>() : fallback;
}

std::string pointer_from_field(const std::string& field) {
  std::string p = "/";
  for (char c : field) {
    if (c == '[' || c == '.') {
      p += '/';
    } else if (c != ']') {
      p += c;
    }
  }
  return p;
}

std::vector<ProductProblem> equal_size_problems(const OutputSpec& spec, const std::string& what) {
  for (size_t i = 1; i < spec.size.size(); ++i)
    if (spec.size[i] != spec.size[0])
      return {{"/size", fmt::format("{}: expected equal sizes, got {}", what,
                                    nlohmann::json(spec.size).dump())}};
  return {};
}

}  // namespace skybake
