// rapidjson does the parsing and the validation; this file adds what its
// 1.1.0 release lacks: readable rules (it reports only a keyword and a
// pointer), duplicate-key detection, and a remote "$ref" provider (its
// GetRemoteDocument passes a length one short, so the URI is re-read up to
// its '#').
#include "pipeline/schema_validator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <rapidjson/document.h>
#include <rapidjson/error/en.h>
#include <rapidjson/schema.h>
#include <rapidjson/stringbuffer.h>

#include "core/error.hpp"
#include "core/json_input.hpp"
#include "core/safe_input.hpp"
#include "core/suggest.hpp"

namespace skybake {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path schema_dir() {
  const char* env = std::getenv("SKYBAKE_SCHEMA_DIR");
  return (env && *env) ? fs::path(env) : fs::path(SKYBAKE_SCHEMA_DIR);
}

bool schema_exists(const std::string& schema) {
  std::error_code ec;
  return fs::is_regular_file(schema_dir() / schema, ec);
}

namespace {

// A string from a preset, cut for a message.
std::string excerpt_text(const std::string& s) {
  return s.size() > 80 ? s.substr(0, 80) + "..." : s;
}

}  // namespace

std::string describe_json(const json& v) {
  switch (v.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return "boolean " + v.dump();
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
      return "integer " + v.dump();
    case json::value_t::number_float:
      return "number " + v.dump();
    case json::value_t::string:
      return "string " + json_excerpt(v);
    case json::value_t::array:
      return "array";
    case json::value_t::object:
      return "object";
    default:
      return "value";
  }
}

// ---------------------------------------------------------------------------
// Strict parsing

namespace {

// rapidjson DOM -> nlohmann, keeping integers integers; reports the first
// duplicate key (rapidjson keeps both members, nlohmann would keep the last).
std::optional<SchemaViolation> convert(const rapidjson::Value& v, const std::string& pointer,
                                       json& out) {
  if (v.IsObject()) {
    out = json::object();
    for (auto it = v.MemberBegin(); it != v.MemberEnd(); ++it) {
      const std::string key(it->name.GetString(), it->name.GetStringLength());
      const std::string child = pointer + (json::json_pointer() / key).to_string();
      if (out.contains(key))
        return SchemaViolation{
            child,
            "duplicateKey",
            fmt::format("duplicate key '{}' (a key may appear once per object)", key),
            {}};
      if (auto bad = convert(it->value, child, out[key])) return bad;
    }
  } else if (v.IsArray()) {
    out = json::array();
    for (rapidjson::SizeType i = 0; i < v.Size(); ++i) {
      out.push_back(nullptr);
      if (auto bad = convert(v[i], pointer + "/" + std::to_string(i), out.back())) return bad;
    }
  } else if (v.IsString()) {
    out = std::string(v.GetString(), v.GetStringLength());
  } else if (v.IsBool()) {
    out = v.GetBool();
  } else if (v.IsUint64()) {
    out = v.GetUint64();
  } else if (v.IsInt64()) {
    out = v.GetInt64();
  } else if (v.IsDouble()) {
    out = v.GetDouble();
  } else {
    out = nullptr;
  }
  return std::nullopt;
}

std::string lower_first(std::string s) {
  if (!s.empty() && s[0] >= 'A' && s[0] <= 'Z') s[0] = char(s[0] - 'A' + 'a');
  while (!s.empty() && (s.back() == '.' || s.back() == ' ')) s.pop_back();
  return s;
}

}  // namespace

std::optional<SchemaViolation> parse_strict_json(const std::string& text, json& out) {
  // Before the parser: rapidjson's parser and convert() recurse per level.
  if (auto deep = json_nesting_problem(text)) return SchemaViolation{"", "syntax", *deep, {}};
  rapidjson::Document doc;
  doc.Parse<rapidjson::kParseValidateEncodingFlag | rapidjson::kParseFullPrecisionFlag>(
      text.data(), text.size());
  if (doc.HasParseError()) {
    const size_t offset = std::min(doc.GetErrorOffset(), text.size());
    size_t line = 1, line_start = 0;
    for (size_t i = 0; i < offset; ++i)
      if (text[i] == '\n') {
        ++line;
        line_start = i + 1;
      }
    std::string reason = lower_first(rapidjson::GetParseError_En(doc.GetParseError()));
    // rapidjson calls a raw newline inside a string an invalid escape.
    if (doc.GetParseError() == rapidjson::kParseErrorStringEscapeInvalid && offset < text.size() &&
        static_cast<unsigned char>(text[offset]) < 0x20)
      reason =
          "a string is not closed before the end of the line (or holds a raw control character)";
    if (doc.GetParseError() == rapidjson::kParseErrorObjectMissName ||
        doc.GetParseError() == rapidjson::kParseErrorValueInvalid)
      reason += " (a trailing comma, a comment, NaN or Infinity are not JSON)";
    return SchemaViolation{"",
                           "syntax",
                           fmt::format("invalid JSON at line {}, column {}: {}", line,
                                       offset - line_start + 1, reason),
                           {}};
  }
  if (auto bad = convert(doc, "", out)) return bad;
  // rapidjson turns a \u escape of a lone low surrogate (\uDC00-\uDFFF
  // with no high one before it) into bytes that are not UTF-8; every later
  // use of the text (messages, the schema check, hashes) needs UTF-8.
  try {
    (void)out.dump();
  } catch (const json::type_error&) {
    return SchemaViolation{"", "syntax",
                           "invalid JSON: a string is not valid Unicode (a \\u escape of a lone "
                           "surrogate, \\uD800-\\uDFFF without its pair)",
                           {}};
  }
  return std::nullopt;
}

// ---------------------------------------------------------------------------
// Schema store: parsed (nlohmann, for messages and defaults) and compiled
// (rapidjson, for validation) copies of each schema file, keyed by path.

namespace {

struct SchemaFile {
  std::string rel;  // relative to the schema folder, '/' separated
  rapidjson::Document raw;
  json tree;
  std::unique_ptr<rapidjson::SchemaDocument> compiled;
};

class SchemaStore : public rapidjson::IRemoteSchemaDocumentProvider {
 public:
  // Caller holds mutex().
  SchemaFile& get(const std::string& rel) {
    const std::string key = (schema_dir() / rel).lexically_normal().string();
    auto it = files_.find(key);
    if (it != files_.end()) {
      if (!it->second->compiled) throw Error("schema $ref cycle through " + key);
      return *it->second;
    }
    // The entry exists (uncompiled) while its own $refs load, to detect cycles.
    auto file = std::make_unique<SchemaFile>();
    SchemaFile& f = *file;
    files_[key] = std::move(file);
    try {
      load(f, rel, key);
    } catch (...) {
      files_.erase(key);
      throw;
    }
    return f;
  }

  const rapidjson::SchemaDocument* GetRemoteDocument(const char* uri,
                                                     rapidjson::SizeType) override {
    std::string name;
    for (const char* c = uri; *c && *c != '#'; ++c) name += *c;
    return get(resolve(bases_.back(), name)).compiled.get();
  }

  // A "$ref" file part relative to the schema `base` that holds it.
  static std::string resolve(const std::string& base, const std::string& ref_file) {
    if (ref_file.empty()) return base;
    return (fs::path(base).parent_path() / ref_file).lexically_normal().generic_string();
  }

  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  static SchemaStore& instance() {
    static SchemaStore store;
    return store;
  }

 private:
  void load(SchemaFile& f, const std::string& rel, const std::string& key) {
    f.rel = fs::path(rel).lexically_normal().generic_string();
    std::ifstream in(key, std::ios::binary);
    if (!in)
      throw IoError(
          fmt::format("cannot read schema {} (is SKYBAKE_SCHEMA_DIR the schemas folder?)", key));
    std::stringstream text;
    text << in.rdbuf();
    if (auto bad = parse_strict_json(text.str(), f.tree))
      throw Error(fmt::format("schema {}: {}: {}", key, bad->pointer, bad->rule));
    f.raw.Parse(text.str().c_str());
    bases_.push_back(f.rel);
    try {
      f.compiled = std::make_unique<rapidjson::SchemaDocument>(f.raw, this);
    } catch (...) {
      bases_.pop_back();
      throw;
    }
    bases_.pop_back();
  }

  std::map<std::string, std::unique_ptr<SchemaFile>> files_;
  std::vector<std::string> bases_;
};

// A node of a parsed schema and the file it sits in (for relative $refs).
struct Node {
  const json* j = nullptr;
  std::string file;
};

// Follows "$ref"s to the schema that applies.
Node resolve_refs(Node n) {
  for (int hops = 0; hops < 32 && n.j && n.j->is_object() && n.j->contains("$ref"); ++hops) {
    const std::string ref = n.j->at("$ref").get<std::string>();
    const size_t hash = ref.find('#');
    const std::string file = SchemaStore::resolve(n.file, ref.substr(0, hash));
    const std::string fragment = hash == std::string::npos ? "" : ref.substr(hash + 1);
    const json& tree = SchemaStore::instance().get(file).tree;
    const json::json_pointer p(fragment);
    n = Node{tree.contains(p) ? &tree.at(p) : nullptr, file};
  }
  return n;
}

// The schema of member `key` (or array item `index`) of a value whose schema is `parent`.
Node child_node(const Node& parent_raw, const std::string& token) {
  const Node parent = resolve_refs(parent_raw);
  if (!parent.j || !parent.j->is_object()) return {};
  const json& s = *parent.j;
  if (s.contains("properties") && s["properties"].contains(token))
    return {&s["properties"][token], parent.file};
  if (s.contains("items")) {
    const json& items = s["items"];
    if (items.is_object()) return {&items, parent.file};
    char* end = nullptr;
    const unsigned long i = std::strtoul(token.c_str(), &end, 10);
    if (items.is_array() && end && *end == '\0' && i < items.size())
      return {&items[i], parent.file};
  }
  if (s.contains("additionalProperties") && s["additionalProperties"].is_object())
    return {&s["additionalProperties"], parent.file};
  return {};
}

std::vector<std::string> split_pointer(const std::string& pointer) {
  std::vector<std::string> tokens;
  const json::json_pointer p(pointer);
  json::json_pointer cur = p;
  while (!cur.empty()) {
    tokens.insert(tokens.begin(), cur.back());
    cur.pop_back();
  }
  return tokens;
}

Node node_at(const Node& root, const std::string& pointer) {
  Node n = root;
  for (const std::string& t : split_pointer(pointer)) {
    n = child_node(n, t);
    if (!n.j) return {};
  }
  return resolve_refs(n);
}

std::string quote_list(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "'" : ", '") + n + "'";
  return s;
}

std::vector<std::string> property_names(const json& schema) {
  std::vector<std::string> names;
  if (schema.contains("properties"))
    for (auto& [k, v] : schema["properties"].items()) names.push_back(k);
  return names;
}

std::string expected_type(const json& schema) {
  if (!schema.contains("type")) return "a valid value";
  const json& t = schema["type"];
  if (t.is_string()) return t.get<std::string>();
  std::string s;
  for (size_t i = 0; i < t.size(); ++i)
    s += (i == 0 ? "" : i + 1 == t.size() ? " or " : ", ") + t[i].get<std::string>();
  return s;
}

// The readable rule for `keyword` failing on `value` (at `pointer`) with schema `s`.
SchemaViolation explain(const std::string& keyword, std::string pointer, const json& doc,
                        const Node& root) {
  SchemaViolation v{pointer, keyword, "", {}};
  if (keyword == "additionalProperties") {
    // rapidjson points at the unknown key itself; its schema is the parent's.
    json::json_pointer p(pointer);
    const std::string key = p.empty() ? "" : p.back();
    if (!p.empty()) p.pop_back();
    const Node parent = node_at(root, p.to_string());
    v.allowed_keys = parent.j ? property_names(*parent.j) : std::vector<std::string>{};
    v.rule = fmt::format("unknown key '{}'{}", key, did_you_mean(key, v.allowed_keys));
    return v;
  }
  const Node node = node_at(root, pointer);
  const json no_schema = json::object();
  const json& s = node.j ? *node.j : no_schema;
  const json::json_pointer jp(pointer);
  const json value = doc.contains(jp) ? doc.at(jp) : json();
  const std::string got = value.is_string() ? "'" + excerpt_text(value.get<std::string>()) + "'"
                                            : json_excerpt(value);

  if (keyword == "type") {
    v.rule = fmt::format("expected {}, got {}", expected_type(s), describe_json(value));
  } else if (keyword == "required") {
    std::vector<std::string> missing;
    if (s.contains("required"))
      for (const json& k : s["required"])
        if (!value.is_object() || !value.contains(k.get<std::string>()))
          missing.push_back(k.get<std::string>());
    v.rule = missing.size() == 1 ? "missing required key '" + missing[0] + "'"
                                 : "missing required keys " + quote_list(missing);
  } else if (keyword == "minimum" || keyword == "maximum") {
    const bool exclusive =
        s.value(keyword == "minimum" ? "exclusiveMinimum" : "exclusiveMaximum", false);
    const char* op = keyword == "minimum" ? (exclusive ? ">" : ">=") : (exclusive ? "<" : "<=");
    v.rule = fmt::format("must be {} {}, got {}", op, s.value(keyword, json()).dump(), got);
  } else if (keyword == "enum") {
    std::vector<std::string> options;
    for (const json& e : s.value("enum", json::array()))
      options.push_back(e.is_string() ? e.get<std::string>() : json_excerpt(e));
    v.rule = fmt::format("expected one of {}, got {}", quote_list(options), got);
    if (value.is_string()) v.rule += did_you_mean(value.get<std::string>(), options);
  } else if (keyword == "minItems" || keyword == "maxItems") {
    const int n = s.value(keyword, 0);
    v.rule =
        fmt::format("expected {} {} item{}, got {}", keyword == "minItems" ? "at least" : "at most",
                    n, n == 1 ? "" : "s", value.size());
  } else if (keyword == "uniqueItems") {
    v.rule = fmt::format("duplicate item {} (each item may appear once)", got);
  } else if (keyword == "minLength") {
    v.rule = "must not be empty";
  } else if (keyword == "maxLength") {
    v.rule = fmt::format("must be at most {} characters", s.value("maxLength", 0));
  } else if (keyword == "pattern") {
    v.rule = fmt::format("{}, got {}",
                         s.value("errorMessage", "must match " + s.value("pattern", std::string())),
                         got);
  } else if (keyword == "minProperties" || keyword == "maxProperties") {
    const std::vector<std::string> names = property_names(s);
    std::vector<std::string> present;
    for (auto& [k, x] : value.items()) present.push_back(k);
    if (s.value("minProperties", 0) == 1 && s.value("maxProperties", 0) == 1)
      v.rule = fmt::format("expected exactly one of {}, got {}", quote_list(names),
                           present.empty() ? "none" : quote_list(present));
    else
      v.rule = fmt::format("has {} keys, outside [{}, {}]", present.size(),
                           s.value("minProperties", 0), s.value("maxProperties", 0));
  } else {
    v.rule = fmt::format("fails schema keyword '{}'", keyword);
  }
  return v;
}

void fill_defaults(json& value, const Node& raw) {
  const Node n = resolve_refs(raw);
  if (!n.j || !n.j->is_object()) return;
  const json& s = *n.j;
  if (value.is_object() && s.contains("properties")) {
    for (auto& [key, prop] : s["properties"].items()) {
      const Node child{&prop, n.file};
      if (!value.contains(key)) {
        // A default beside a "$ref" wins over one inside the referenced schema.
        const Node target = resolve_refs(child);
        if (prop.contains("default"))
          value[key] = prop["default"];
        else if (target.j && target.j->contains("default"))
          value[key] = target.j->at("default");
        else
          continue;
      }
      fill_defaults(value[key], child);
    }
  } else if (value.is_array() && s.contains("items") && s["items"].is_object()) {
    for (json& item : value) fill_defaults(item, Node{&s["items"], n.file});
  }
}

}  // namespace

std::optional<SchemaViolation> validate_against_schema(const json& doc, const std::string& schema) {
  std::lock_guard<std::mutex> lock(SchemaStore::mutex());
  SchemaFile& file = SchemaStore::instance().get(schema);
  rapidjson::Document rdoc;
  const std::string text = doc.dump();
  rdoc.Parse<rapidjson::kParseFullPrecisionFlag>(text.c_str());
  rapidjson::SchemaValidator validator(*file.compiled);
  if (rdoc.Accept(validator)) return std::nullopt;
  rapidjson::StringBuffer pointer;
  validator.GetInvalidDocumentPointer().Stringify(pointer);
  const char* keyword = validator.GetInvalidSchemaKeyword();
  return explain(keyword ? keyword : "", pointer.GetString(), doc, Node{&file.tree, file.rel});
}

namespace {

// A value the schema at `raw` accepts, to stand in for an invalid one.
std::optional<json> stand_in(const Node& raw, int depth = 0) {
  const Node n = resolve_refs(raw);
  if (depth > 16 || !n.j || !n.j->is_object()) return std::nullopt;
  const json& s = *n.j;
  if (s.contains("default")) return s["default"];
  if (s.contains("enum") && s["enum"].is_array() && !s["enum"].empty()) return s["enum"][0];
  std::string type;
  if (s.contains("type")) type = s["type"].is_array() ? s["type"][0].get<std::string>()
                                                      : s["type"].get<std::string>();
  if (type == "object" || (type.empty() && s.contains("properties"))) {
    json object = json::object();
    const json properties = s.value("properties", json::object());
    for (const json& key : s.value("required", json::array())) {
      const std::string k = key.get<std::string>();
      if (!properties.contains(k)) return std::nullopt;
      const std::optional<json> v = stand_in(Node{&s["properties"][k], n.file}, depth + 1);
      if (!v) return std::nullopt;
      object[k] = *v;
    }
    if (object.empty() && s.value("minProperties", 0) > 0 && !properties.empty()) {
      const std::string k = properties.begin().key();
      const std::optional<json> v = stand_in(Node{&s["properties"][k], n.file}, depth + 1);
      if (!v) return std::nullopt;
      object[k] = *v;
    }
    return object;
  }
  if (type == "array") {
    json array = json::array();
    for (int i = 0; i < s.value("minItems", 0); ++i) {
      const json* items = s.contains("items") ? &s["items"] : nullptr;
      if (items && items->is_array())
        items = size_t(i) < items->size() ? &(*items)[size_t(i)] : nullptr;
      const std::optional<json> v = items ? stand_in(Node{items, n.file}, depth + 1) : json();
      if (!v) return std::nullopt;
      array.push_back(*v);
    }
    return array;
  }
  if (type == "string") return std::string(size_t(std::max(1, s.value("minLength", 1))), 'a');
  if (type == "integer" || type == "number") {
    const bool has_lo = s.contains("minimum"), has_hi = s.contains("maximum");
    const double lo = s.value("minimum", 0.0), hi = s.value("maximum", 0.0);
    const bool open_lo = s.value("exclusiveMinimum", false);
    const bool open_hi = s.value("exclusiveMaximum", false);
    if (type == "integer") {
      double v = has_lo ? std::ceil(lo) : has_hi ? std::floor(hi) : 0.0;
      if (has_lo && open_lo && v == lo) v += 1.0;
      if (!has_lo && has_hi && open_hi && v == hi) v -= 1.0;
      return json(int64_t(v));
    }
    if (has_lo && has_hi) return json((lo + hi) / 2);
    if (has_lo) return json(open_lo ? lo + 1.0 : lo);
    if (has_hi) return json(open_hi ? hi - 1.0 : hi);
    return json(0.0);
  }
  if (type == "boolean") return json(false);
  if (type == "null") return json();
  return std::nullopt;
}

// Replaces or removes what `v` points at in `doc` so that the schema accepts
// it; false when nothing would.
bool patch(json& doc, const SchemaViolation& v, const std::string& schema) {
  std::lock_guard<std::mutex> lock(SchemaStore::mutex());
  SchemaFile& file = SchemaStore::instance().get(schema);
  const Node root{&file.tree, file.rel};
  json::json_pointer at(v.pointer);
  if (v.keyword == "additionalProperties") {
    if (at.empty()) return false;
    const std::string key = at.back();
    at.pop_back();
    if (!doc.contains(at) || !doc.at(at).is_object()) return false;
    json& object = doc.at(at);
    // A misspelled required key is read as the key it was meant to be, so
    // that the same mistake is not reported again as a missing key.
    const Node node = node_at(root, at.to_string());
    const std::string* meant =
        closest_name(key, v.allowed_keys, std::max<size_t>(2, key.size() / 3));
    bool required = false;
    if (meant && node.j && node.j->is_object())
      for (const json& r : node.j->value("required", json::array()))
        required = required || r == *meant;
    if (required && !object.contains(*meant)) object[*meant] = object[key];
    object.erase(key);
    return true;
  }
  if (!doc.contains(at)) return false;
  if (v.keyword == "uniqueItems" && !at.empty()) {  // `at` is the repeated item: drop it
    const std::string index = at.back();
    json::json_pointer array = at.parent_pointer();
    if (doc.at(array).is_array()) {
      doc.at(array).erase(std::stoul(index));
      return true;
    }
  }
  json& value = doc.at(at);
  if (v.keyword == "required" && value.is_object()) {
    const Node node = node_at(root, v.pointer);
    if (!node.j || !node.j->is_object()) return false;
    for (const json& key : node.j->value("required", json::array())) {
      const std::string k = key.get<std::string>();
      if (value.contains(k)) continue;
      const std::optional<json> stand = stand_in(child_node(node, k));
      if (!stand) return false;
      value[k] = *stand;
    }
    return true;
  }
  if (at.empty()) return false;  // the document itself has the wrong shape
  const Node node = node_at(root, v.pointer);
  std::optional<json> stand = stand_in(node);
  // An item of an array stands in by an allowed value its siblings do not
  // hold, so that no duplicate is reported that the document does not have.
  const json& parent = doc.at(at.parent_pointer());
  if (parent.is_array() && node.j && node.j->contains("enum"))
    for (const json& option : node.j->at("enum"))
      if (std::find(parent.begin(), parent.end(), option) == parent.end()) {
        stand = option;
        break;
      }
  if (!stand || *stand == value) return false;
  value = *stand;
  return true;
}

}  // namespace

std::vector<SchemaViolation> validate_against_schema_all(const json& doc, const std::string& schema,
                                                         size_t max, json* patched) {
  json work = doc;
  std::vector<SchemaViolation> found;
  bool valid = false;
  while (found.size() < max) {
    const std::optional<SchemaViolation> v = validate_against_schema(work, schema);
    if (!v) {
      valid = true;
      break;
    }
    for (const SchemaViolation& seen : found)
      if (seen.pointer == v->pointer && seen.keyword == v->keyword) {
        if (patched) *patched = json();
        return found;  // its stand-in did not satisfy the schema
      }
    found.push_back(*v);
    if (!patch(work, *v, schema)) break;
  }
  if (patched) *patched = valid ? std::move(work) : json();
  return found;
}

void apply_schema_defaults(json& doc, const std::string& schema) {
  std::lock_guard<std::mutex> lock(SchemaStore::mutex());
  SchemaFile& file = SchemaStore::instance().get(schema);
  fill_defaults(doc, Node{&file.tree, file.rel});
}

std::vector<std::string> schema_property_names(const std::string& schema) {
  std::lock_guard<std::mutex> lock(SchemaStore::mutex());
  SchemaFile& file = SchemaStore::instance().get(schema);
  const Node root = resolve_refs(Node{&file.tree, file.rel});
  return root.j ? property_names(*root.j) : std::vector<std::string>{};
}

}  // namespace skybake
