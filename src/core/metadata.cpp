#include "core/metadata.hpp"

#include <fmt/format.h>

#include "core/error.hpp"

namespace skybake {

namespace {

template <class T>
const char* type_name_of();
template <> const char* type_name_of<int>() { return "int"; }
template <> const char* type_name_of<double>() { return "double"; }
template <> const char* type_name_of<std::string>() { return "string"; }
template <> const char* type_name_of<glm::ivec2>() { return "int2"; }
template <> const char* type_name_of<glm::ivec3>() { return "int3"; }
template <> const char* type_name_of<glm::dvec2>() { return "double2"; }
template <> const char* type_name_of<glm::dvec3>() { return "double3"; }

std::string number_text(int v) { return std::to_string(v); }
// The shortest text that reads back as the same double (fmt's "{}", Dragonbox):
// 0.09, not 0.089999999999999997.
std::string number_text(double v) { return fmt::format("{}", v); }

template <class V>
std::string vector_text(const V& v) {
  std::string s = "[";
  for (int i = 0; i < V::length(); ++i) s += (i ? ", " : "") + number_text(v[i]);
  return s + "]";
}

template <class T>
T get_meta(const Metadata& meta, const std::string& key) {
  const auto it = meta.find(key);
  if (it == meta.end()) throw Error(fmt::format("metadata '{}': missing", key));
  if (const T* v = std::get_if<T>(&it->second)) return *v;
  throw Error(fmt::format("metadata '{}': expected {}, got {} {}", key, type_name_of<T>(),
                          meta_type_name(it->second), meta_text(it->second)));
}

}  // namespace

std::string meta_type_name(const MetaValue& value) {
  return std::visit([](const auto& v) { return std::string(type_name_of<std::decay_t<decltype(v)>>()); },
                    value);
}

std::string meta_text(const MetaValue& value) {
  struct Text {
    std::string operator()(int v) const { return number_text(v); }
    std::string operator()(double v) const { return number_text(v); }
    std::string operator()(const std::string& v) const { return v; }
    std::string operator()(const glm::ivec2& v) const { return vector_text(v); }
    std::string operator()(const glm::ivec3& v) const { return vector_text(v); }
    std::string operator()(const glm::dvec2& v) const { return vector_text(v); }
    std::string operator()(const glm::dvec3& v) const { return vector_text(v); }
  };
  return std::visit(Text{}, value);
}

void set_meta(Metadata& meta, const std::string& key, const std::string& value) {
  meta[key] = value;
}
void set_meta(Metadata& meta, const std::string& key, const char* value) {
  meta[key] = std::string(value);
}
void set_meta(Metadata& meta, const std::string& key, double value) { meta[key] = value; }
void set_meta(Metadata& meta, const std::string& key, int value) { meta[key] = value; }
void set_meta(Metadata& meta, const std::string& key, glm::ivec2 value) { meta[key] = value; }
void set_meta(Metadata& meta, const std::string& key, glm::ivec3 value) { meta[key] = value; }
void set_meta(Metadata& meta, const std::string& key, glm::dvec2 value) { meta[key] = value; }
void set_meta(Metadata& meta, const std::string& key, glm::dvec3 value) { meta[key] = value; }

int meta_int(const Metadata& meta, const std::string& key) { return get_meta<int>(meta, key); }
double meta_double(const Metadata& meta, const std::string& key) {
  return get_meta<double>(meta, key);
}
std::string meta_string(const Metadata& meta, const std::string& key) {
  return get_meta<std::string>(meta, key);
}
glm::ivec2 meta_int2(const Metadata& meta, const std::string& key) {
  return get_meta<glm::ivec2>(meta, key);
}
glm::ivec3 meta_int3(const Metadata& meta, const std::string& key) {
  return get_meta<glm::ivec3>(meta, key);
}
glm::dvec2 meta_double2(const Metadata& meta, const std::string& key) {
  return get_meta<glm::dvec2>(meta, key);
}
glm::dvec3 meta_double3(const Metadata& meta, const std::string& key) {
  return get_meta<glm::dvec3>(meta, key);
}

}  // namespace skybake
