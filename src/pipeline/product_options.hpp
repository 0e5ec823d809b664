// What a product's baker and its semantic checks read from an output object:
// typed options with defaults, JSON pointers for a baker spec's fields, and
// the shared rule of square / cube products.
#pragma once

#include <string>
#include <vector>

#include "pipeline/product.hpp"

namespace skybake {

// Reads an integer / number / string option of a product from the output
// object, with a default (the schema has already checked types and ranges).
int option_int(const OutputSpec& spec, const std::string& key, int fallback);
double option_double(const OutputSpec& spec, const std::string& key, double fallback);
std::string option_string(const OutputSpec& spec, const std::string& key,
                          const std::string& fallback);

// A baker spec's field name as a JSON pointer relative to the output or
// section: "worley[2].octaves" -> "/worley/2/octaves".
std::string pointer_from_field(const std::string& field);

// A square / cube product's rule: every size axis equal. `what` says why
// ("the texture is a cube (square) and tiles on every axis").
std::vector<ProductProblem> equal_size_problems(const OutputSpec& spec, const std::string& what);

}  // namespace skybake
