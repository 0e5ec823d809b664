// Metadata values as JSON (manifest.json, `skybake info --json`): int and
// double as JSON numbers (a double always with a fraction or exponent, so
// that it reads back as a double: 2.0, not 2), string as a string, int2/int3
// and double2/double3 as arrays of 2 or 3 numbers. A non-finite double is written as null (JSON has no NaN) and
// read back as NaN.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/metadata.hpp"

namespace skybake {

nlohmann::json meta_to_json(const MetaValue& value);
nlohmann::json metadata_to_json(const Metadata& meta);

// The value a JSON value written by meta_to_json stands for, or nullopt with
// `why` set ("expected ..., got ...") when it is none of the shapes above.
std::optional<MetaValue> meta_from_json(const nlohmann::json& j, std::string* why = nullptr);

// Every entry of a JSON object; throws Error "metadata/<key>: <why>" on the
// first value meta_from_json refuses, or when `j` is not an object.
Metadata metadata_from_json(const nlohmann::json& j);

}  // namespace skybake
