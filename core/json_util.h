// Typed reads from parsed JSON whose errors name the file and the item
// ("cases/x.json: pairs[3].a.radius: expected a finite number, got \"1\"").
#pragma once
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "core/vec.h"

namespace revdist {

using Json = nlohmann::json;

// Reads and parses a whole JSON file; InputError if it cannot be opened, is not a
// regular-sized text (more than 64 MiB, a NUL byte, a directory), is not JSON, nests
// deeper than 64 levels or repeats a key inside one object.
Json read_json_file(const std::string& path);
// The same checks on text already in memory (path only names it in messages).
Json parse_json_text(const std::string& text, const std::string& path);

// The range of coordinates, rates and radii every input file keeps (case and
// circle files): squares and products of a few lengths must neither overflow
// nor underflow for the engines' rounding allowances to hold.
constexpr double kMaxMagnitude = 1e100;

// s in double quotes with JSON escapes (control characters, quotes, backslashes), cut
// after 80 bytes: a name from the input always prints as one readable line.
std::string quote(const std::string& s);

// Context for error messages: the file and a path inside it.
struct JsonWhere {
  std::string file;
  std::string item;  // e.g. "pairs[3].a"
  JsonWhere operator/(const std::string& key) const;  // item + "." + key
  JsonWhere operator[](std::size_t index) const;      // item + "[i]"
  [[noreturn]] void fail(const std::string& problem) const;
};

// A finite number (NaN and infinity are rejected, as is any non-number).
double read_number(const Json& j, const JsonWhere& where);
// An array of exactly two / three finite numbers.
Vec2 read_vec2(const Json& j, const JsonWhere& where);
Vec3 read_vec3(const Json& j, const JsonWhere& where);
// A member that must be present in object j.
const Json& require(const Json& j, const std::string& key, const JsonWhere& where);
// The object j must have a string member "format" equal to expected.
void require_format(const Json& j, const std::string& expected, const JsonWhere& where);
// Every member of object j is in `allowed` or is "comment".
void reject_unknown_members(const Json& j, const std::set<std::string>& allowed, const JsonWhere& where);

}  // namespace revdist
