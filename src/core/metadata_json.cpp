#include "core/metadata_json.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/json_input.hpp"

namespace skybake {

namespace {

using nlohmann::json;

json number_json(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

bool is_int32(const json& v) {
  if (v.is_number_unsigned()) return v.get<uint64_t>() <= uint64_t(std::numeric_limits<int>::max());
  if (v.is_number_integer())
    return v.get<int64_t>() >= std::numeric_limits<int>::min() &&
           v.get<int64_t>() <= std::numeric_limits<int>::max();
  return false;
}

// An array of 2 or 3 numbers: all integers (int2/int3) or all written as
// doubles (a float, or null for a non-finite double).
std::optional<MetaValue> vector_from_json(const json& j, std::string* why) {
  bool ints = true, doubles = true;
  for (const json& v : j) {
    ints = ints && is_int32(v);
    doubles = doubles && (v.is_number_float() || v.is_null());
  }
  const auto d = [](const json& v) {
    return v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>();
  };
  if (ints && j.size() == 2) return glm::ivec2(j[0].get<int>(), j[1].get<int>());
  if (ints && j.size() == 3) return glm::ivec3(j[0].get<int>(), j[1].get<int>(), j[2].get<int>());
  if (doubles && j.size() == 2) return glm::dvec2(d(j[0]), d(j[1]));
  if (doubles && j.size() == 3) return glm::dvec3(d(j[0]), d(j[1]), d(j[2]));
  if (why)
    *why = fmt::format("expected 2 or 3 integers or 2 or 3 non-integer numbers, got {}",
                       json_excerpt(j));
  return std::nullopt;
}

}  // namespace

json meta_to_json(const MetaValue& value) {
  struct ToJson {
    json operator()(int v) const { return v; }
    json operator()(double v) const { return number_json(v); }
    json operator()(const std::string& v) const { return v; }
    json operator()(const glm::ivec2& v) const { return {v.x, v.y}; }
    json operator()(const glm::ivec3& v) const { return {v.x, v.y, v.z}; }
    json operator()(const glm::dvec2& v) const { return {number_json(v.x), number_json(v.y)}; }
    json operator()(const glm::dvec3& v) const {
      return {number_json(v.x), number_json(v.y), number_json(v.z)};
    }
  };
  return std::visit(ToJson{}, value);
}

json metadata_to_json(const Metadata& meta) {
  json out = json::object();
  for (const auto& [key, value] : meta) out[key] = meta_to_json(value);
  return out;
}

std::optional<MetaValue> meta_from_json(const json& j, std::string* why) {
  if (j.is_string()) return j.get<std::string>();
  if (j.is_number_float()) return j.get<double>();
  if (j.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (is_int32(j)) return j.get<int>();
  if (j.is_array()) return vector_from_json(j, why);
  if (why)
    *why = fmt::format("expected an int, a number, a string or 2 or 3 numbers, got {}",
                       json_excerpt(j));
  return std::nullopt;
}

Metadata metadata_from_json(const json& j) {
  if (!j.is_object()) throw Error(fmt::format("metadata: expected an object, got {}", json_excerpt(j)));
  Metadata meta;
  for (const auto& [key, value] : j.items()) {
    std::string why;
    std::optional<MetaValue> v = meta_from_json(value, &why);
    if (!v) throw Error(fmt::format("metadata/{}: {}", key, why));
    meta[key] = *v;
  }
  return meta;
}

}  // namespace skybake
