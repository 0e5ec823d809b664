#include "io/shader_constants.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/file_record.hpp"

namespace skybake {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// One constant as a shader declares it: type and literal, or nothing (a
// comment) for a value no shader type holds.
struct Literal {
  std::string type;   // "int", "uint", "float", "bool"; "" = comment only
  std::string value;  // the literal, or the text of the comment
};

std::string float_literal(double v) {
  std::string s = fmt::format("{:.17g}", v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

Literal integer_literal(long long v) {
  if (v >= std::numeric_limits<int32_t>::min() && v <= std::numeric_limits<int32_t>::max())
    return {"int", std::to_string(v)};
  if (v > 0 && v <= std::numeric_limits<uint32_t>::max()) return {"uint", std::to_string(v) + "u"};
  return {"float", float_literal(double(v))};
}

Literal number_literal(double v) {
  if (!std::isfinite(v) || std::abs(v) > double(std::numeric_limits<float>::max()))
    return {"", fmt::format("{:.17g} (outside the float32 range)", v)};
  return {"float", float_literal(v)};
}

// Metadata recorded as text: a number written out in full is a number.
Literal literal_from_text(const std::string& s) {
  if (s == "true" || s == "false") return {"bool", s};
  if (s.empty() || std::isspace(static_cast<unsigned char>(s.front()))) return {"", s};
  const bool integer = s.find_first_not_of("-0123456789") == std::string::npos;
  char* end = nullptr;
  errno = 0;
  if (integer) {
    // Beyond 32 bits an integer written as text is an identifier (a hash),
    // not a quantity.
    const long long v = std::strtoll(s.c_str(), &end, 10);
    if (*end == '\0' && errno == 0 && v >= std::numeric_limits<int32_t>::min() &&
        v <= std::numeric_limits<uint32_t>::max())
      return integer_literal(v);
    return {"", s};
  }
  const double v = std::strtod(s.c_str(), &end);
  if (*end == '\0' && errno == 0 && s.find_first_of("xXnN") == std::string::npos)
    return number_literal(v);
  return {"", s};
}

// int2/int3 and double2/double3 metadata: JSON arrays of 2 or 3 numbers.
Literal vector_literal(const json& v, ShaderLanguage language) {
  bool integers = true;
  for (const json& e : v) {
    if (!e.is_number()) return {"", v.dump()};
    integers &= e.is_number_integer();
  }
  std::string values;
  for (const json& e : v) {
    const Literal l =
        integers ? integer_literal(e.get<long long>()) : number_literal(e.get<double>());
    if (l.type != (integers ? "int" : "float")) return {"", v.dump()};
    values += (values.empty() ? "" : ", ") + l.value;
  }
  const bool glsl = language == ShaderLanguage::glsl;
  const char* base = integers ? (glsl ? "ivec" : "int") : (glsl ? "vec" : "float");
  const std::string type = fmt::format("{}{}", base, v.size());
  return {type, fmt::format("{}({})", type, values)};
}

Literal literal_from_json(const json& v, ShaderLanguage language) {
  if (v.is_array() && (v.size() == 2 || v.size() == 3)) return vector_literal(v, language);
  if (v.is_boolean()) return {"bool", v.get<bool>() ? "true" : "false"};
  if (v.is_number_unsigned()) {
    const uint64_t u = v.get<uint64_t>();
    return u <= uint64_t(std::numeric_limits<long long>::max()) ? integer_literal((long long)u)
                                                                : number_literal(double(u));
  }
  if (v.is_number_integer()) return integer_literal(v.get<long long>());
  if (v.is_number_float()) return number_literal(v.get<double>());
  if (v.is_string()) return literal_from_text(v.get<std::string>());
  return {"", v.dump()};
}

// Comments hold printable ASCII on one line: some shader compilers refuse
// other bytes even there.
std::string comment_text(const std::string& s) {
  std::string out;
  for (char c : s) out += (c >= 0x20 && c < 0x7f) ? c : ' ';
  return out;
}

std::string declaration(ShaderLanguage language, const Literal& l, const std::string& name) {
  return fmt::format("{}const {} {} = {};\n", language == ShaderLanguage::hlsl ? "static " : "",
                     l.type, name, l.value);
}

// Unique names in key order: the second key that maps to a name gets _2.
class Names {
 public:
  std::string take(const std::string& base) {
    std::string name = base;
    for (int k = 2; !taken_.insert(name).second; ++k) name = fmt::format("{}_{}", base, k);
    return name;
  }

 private:
  std::set<std::string> taken_;
};

}  // namespace

const char* shader_language_name(ShaderLanguage language) {
  return language == ShaderLanguage::glsl ? "glsl" : "hlsl";
}

std::string shader_identifier(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (std::isalnum(static_cast<unsigned char>(c)))
      out += char(std::toupper(static_cast<unsigned char>(c)));
    else if (!out.empty() && out.back() != '_')
      out += '_';
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out;
}

std::string shader_constants_text(const ManifestEntry& entry, ShaderLanguage language,
                                  const std::string& tool) {
  const std::string prefix = "SKYBAKE_" + shader_identifier(entry.name);
  const std::string guard = prefix + "_" + (language == ShaderLanguage::glsl ? "GLSL" : "HLSL");
  std::string out = fmt::format(
      "// Generated by {} from manifest.json: the constants of output \"{}\" (product {}).\n"
      "// Do not edit: `skybake bake --emit-shader-constants` writes it again.\n"
      "#ifndef {}\n#define {}\n\n",
      comment_text(tool), comment_text(entry.name), comment_text(entry.product), guard, guard);
  // Metadata that records a dimension itself ("width") keeps the name.
  std::set<std::string> metadata_ids;
  for (const auto& item : entry.metadata.items())
    if (!literal_from_json(item.value(), language).type.empty())
      metadata_ids.insert(prefix + "_" + shader_identifier(item.key()));
  Names names;
  auto dimension = [&](const char* axis, int value) {
    const std::string name = prefix + "_" + axis;
    if (!metadata_ids.count(name))
      out += declaration(language, integer_literal(value), names.take(name));
  };
  const char* axes[3] = {"WIDTH", "HEIGHT", "DEPTH"};
  for (size_t i = 0; i < entry.dimensions.size() && i < 3; ++i)
    dimension(axes[i], entry.dimensions[i]);
  if (entry.layers > 1) dimension("LAYERS", entry.layers);
  std::string channels;
  for (const std::string& c : entry.channels) channels += (channels.empty() ? "" : " ") + c;
  out += fmt::format("// channels: {}\n", comment_text(channels));
  for (const auto& [key, value] : entry.metadata.items()) {
    const Literal l = literal_from_json(value, language);
    const std::string id = shader_identifier(key);
    if (l.type.empty() || id.empty())
      out += fmt::format("// {}: {}\n", comment_text(key), comment_text(l.value));
    else
      out += declaration(language, l, names.take(prefix + "_" + id));
  }
  out += fmt::format("\n#endif  // {}\n", guard);
  return out;
}

std::vector<fs::path> emit_shader_constants(const fs::path& scene_dir,
                                            const std::vector<std::string>& outputs,
                                            const std::string& tool) {
  std::vector<fs::path> written;
  if (outputs.empty()) return written;
  DirectoryLock lock(scene_dir);
  const fs::path manifest_file = scene_dir / "manifest.json";
  Manifest m = read_manifest(manifest_file);
  for (const std::string& name : outputs) {
    auto it = m.entries.find(name);
    if (it == m.entries.end())
      throw IoError(fmt::format("{}: no output '{}' to write shader constants for",
                                manifest_file.string(), name));
    ManifestEntry& entry = it->second;
    std::vector<ManifestFile> files;
    for (const ManifestFile& f : entry.files)
      if (f.format != "glsl" && f.format != "hlsl") files.push_back(f);
    for (ShaderLanguage language : {ShaderLanguage::glsl, ShaderLanguage::hlsl}) {
      const std::string file = name + "." + shader_language_name(language);
      write_text_atomic(scene_dir / file, shader_constants_text(entry, language, tool));
      files.push_back({file, shader_language_name(language), "text",
                       stat_file(scene_dir / file).size, hash_file(scene_dir / file)});
      written.push_back(scene_dir / file);
    }
    entry.files = std::move(files);
  }
  write_manifest(manifest_file, m);
  return written;
}

}  // namespace skybake
