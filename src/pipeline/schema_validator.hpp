// Strict JSON parsing and JSON Schema (draft-04) validation of presets, with
// rapidjson (the only JSON Schema validator packaged in Debian), and
// the translation of its first error into one readable rule ("must be >= 0,
// got -1", "unknown key 'x' (did you mean 'y'?)"). rapidjson 1.1.0 only
// reports the failing keyword and document pointer, so the rule is rebuilt
// from our own copy of the schema at that pointer.
//
// Schemas live in schema_dir(): $SKYBAKE_SCHEMA_DIR when set (installed
// binaries, tests), else the compiled-in SKYBAKE_SCHEMA_DIR. They are parsed
// and compiled once per process and cached (thread-safe). Cross-file "$ref"s
// ("atmosphere.schema.json#") resolve relative to the referencing schema.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace skybake {

// A document failed a schema or the JSON syntax.
struct SchemaViolation {
  std::string pointer;  // JSON pointer of the offending value in the document, "" = root
  std::string keyword;  // the failing schema keyword ("minimum", "additionalProperties", ...)
                        // or "syntax" / "duplicateKey" for parse errors
  std::string rule;     // readable rule: "must be >= 0, got -1"
  std::vector<std::string> allowed_keys;  // additionalProperties only: the keys the schema knows
};

// The schema folder: $SKYBAKE_SCHEMA_DIR if set and not empty, else the compiled-in one.
std::filesystem::path schema_dir();

// True when `schema` (relative to schema_dir(), e.g. "products/transmittance.schema.json")
// exists.
bool schema_exists(const std::string& schema);

// Parses strict JSON: no comments, no trailing commas, no NaN/Infinity, no
// number too big for a double (1e400), valid UTF-8, no key twice in an object.
// On failure returns the problem (syntax errors carry "line L, column C");
// integers stay integers in `out`.
std::optional<SchemaViolation> parse_strict_json(const std::string& text, nlohmann::json& out);

// Validates `doc` against `schema` (relative to schema_dir()). nullopt when
// valid, else the first violation in document order. Throws IoError when the
// schema file cannot be read, Error when it is not valid JSON.
std::optional<SchemaViolation> validate_against_schema(const nlohmann::json& doc,
                                                       const std::string& schema);

// Every violation of `doc` against `schema`, at most `max`: after each one the
// offending value is replaced by one the schema accepts (its default, its
// first enum value, its minimum, an object of its required keys...) or an
// unknown key is dropped, and the document is validated again, so each
// violation is found in the document as written. `patched` (optional)
// receives the document with those replacements when it then passes the
// schema, else null: when a value has no stand-in or `max` was reached.
std::vector<SchemaViolation> validate_against_schema_all(const nlohmann::json& doc,
                                                         const std::string& schema, size_t max,
                                                         nlohmann::json* patched = nullptr);

// Inserts the "default" of every property that `schema` declares and `doc`
// lacks, recursively through present objects and array items (following
// "$ref"). The schemas are the single source of defaults.
void apply_schema_defaults(nlohmann::json& doc, const std::string& schema);

// Names of the properties a schema's root object declares (for messages).
std::vector<std::string> schema_property_names(const std::string& schema);

// "integer 3", "string \"abc\"", "array" ...: how messages name a JSON value's type.
std::string describe_json(const nlohmann::json& value);

}  // namespace skybake
