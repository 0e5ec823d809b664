// Typed metadata of a Texture: what writers copy into file headers (EXR
// attributes, VDB grid metadata) and the manifest, and what an engine reads
// back as values rather than text. docs/formats.md "Metadata" lists the keys.
//
// A value is one of: int (32 bits, as EXR's int attribute), double, string
// (text only), int2/int3 or double2/double3 (glm vectors: small fixed-size
// numeric tuples such as the solar irradiance per channel). Numbers are never
// stored as text. There is no list type: EXR and VDB have none for doubles,
// so a list of varying length is one key per element ("layer.0.altitude_m").
#pragma once

#include <map>
#include <string>
#include <variant>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace skybake {

using MetaValue = std::variant<int, double, std::string, glm::ivec2, glm::ivec3, glm::dvec2,
                               glm::dvec3>;
using Metadata = std::map<std::string, MetaValue>;

// The type's name as docs/formats.md "Metadata" writes it: "int", "double",
// "string", "int2", "int3", "double2", "double3".
std::string meta_type_name(const MetaValue& value);

// The value as a person reads it: doubles in the shortest text that reads
// back as the same double ("0.09", "1e-300"), vectors as "[a, b, c]",
// strings as they are.
std::string meta_text(const MetaValue& value);

// Sets a value. Call sites pass the natural C++ type; there is no conversion
// to text.
void set_meta(Metadata& meta, const std::string& key, const std::string& value);
void set_meta(Metadata& meta, const std::string& key, const char* value);
void set_meta(Metadata& meta, const std::string& key, double value);
void set_meta(Metadata& meta, const std::string& key, int value);
void set_meta(Metadata& meta, const std::string& key, glm::ivec2 value);
void set_meta(Metadata& meta, const std::string& key, glm::ivec3 value);
void set_meta(Metadata& meta, const std::string& key, glm::dvec2 value);
void set_meta(Metadata& meta, const std::string& key, glm::dvec3 value);

// Typed readers. Each throws Error "metadata 'key': missing" when the key is
// absent and "metadata 'key': expected <type>, got <type> <value>" when it
// holds another type; none converts (an int is not read as a double).
int meta_int(const Metadata& meta, const std::string& key);
double meta_double(const Metadata& meta, const std::string& key);
std::string meta_string(const Metadata& meta, const std::string& key);
glm::ivec2 meta_int2(const Metadata& meta, const std::string& key);
glm::ivec3 meta_int3(const Metadata& meta, const std::string& key);
glm::dvec2 meta_double2(const Metadata& meta, const std::string& key);
glm::dvec3 meta_double3(const Metadata& meta, const std::string& key);

// The value of `key` if it holds a T, else nullptr (absent or another type).
template <class T>
const T* find_meta(const Metadata& meta, const std::string& key) {
  const auto it = meta.find(key);
  return it == meta.end() ? nullptr : std::get_if<T>(&it->second);
}

}  // namespace skybake
