// Typed JSON reads with file/item-naming errors (SPEC section 3, bad input).
#include "core/json_util.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/input_error.h"

namespace revdist {

Json read_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  try {
    return Json::parse(buffer.str());
  } catch (const Json::exception& e) {
    // parse_error for bad syntax, out_of_range 406 for numbers such as 1e999 that overflow a
    // double. nlohmann's message is one line: "[json.exception.parse_error.101] parse error at line 1, ..."
    std::string what = e.what();
    const auto pos = what.find("] ");
    if (pos != std::string::npos) what = what.substr(pos + 2);
    throw InputError(path + ": not JSON: " + what);
  }
}

JsonWhere JsonWhere::operator/(const std::string& key) const {
  return {file, item.empty() ? key : item + "." + key};
}

JsonWhere JsonWhere::operator[](std::size_t index) const {
  return {file, item + "[" + std::to_string(index) + "]"};
}

void JsonWhere::fail(const std::string& problem) const {
  throw InputError(file + ": " + (item.empty() ? std::string("top level") : item) + ": " + problem);
}

namespace {
std::string short_dump(const Json& j) {
  std::string s = j.dump();
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}
}  // namespace

double read_number(const Json& j, const JsonWhere& where) {
  if (!j.is_number()) where.fail("expected a finite number, got " + short_dump(j));
  const double v = j.get<double>();
  if (!std::isfinite(v)) where.fail("expected a finite number, got " + short_dump(j));
  return v;
}

namespace {
template <int N>
Eigen::Matrix<double, N, 1> read_vec(const Json& j, const JsonWhere& where) {
  if (!j.is_array() || j.size() != N)
    where.fail("expected an array of " + std::to_string(N) + " numbers, got " + short_dump(j));
  Eigen::Matrix<double, N, 1> v;
  for (int i = 0; i < N; ++i) v[i] = read_number(j[i], where[i]);
  return v;
}
}  // namespace

Vec2 read_vec2(const Json& j, const JsonWhere& where) { return read_vec<2>(j, where); }
Vec3 read_vec3(const Json& j, const JsonWhere& where) { return read_vec<3>(j, where); }

const Json& require(const Json& j, const std::string& key, const JsonWhere& where) {
  if (!j.is_object()) where.fail("expected an object, got " + short_dump(j));
  const auto it = j.find(key);
  if (it == j.end()) where.fail("missing \"" + key + "\"");
  return *it;
}

void require_format(const Json& j, const std::string& expected, const JsonWhere& where) {
  const Json& f = require(j, "format", where);
  if (!f.is_string() || f.get<std::string>() != expected)
    (where / "format").fail("expected \"" + expected + "\", got " + short_dump(f));
}

}  // namespace revdist
