// Typed JSON reads with file/item-naming errors (SPEC section 3, bad input).
#include "core/json_util.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <set>
#include <vector>

#include "core/input_error.h"

namespace revdist {

namespace {

// Limits that keep hostile input a one-line error rather than a crash or an endless read.
// The bundled cases nest 6 levels deep and the largest is under 1 MiB.
constexpr int kMaxDepth = 64;
constexpr std::size_t kMaxBytes = std::size_t{64} << 20;

// Reads at most kMaxBytes + 1 bytes: /dev/zero, a pipe that never ends or a huge file
// stops here, not when memory runs out.
std::string read_capped(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(path + ": cannot open file (" + std::strerror(errno) + ")");
  struct stat st {};
  if (::fstat(fd, &st) == 0) {
    if (S_ISDIR(st.st_mode)) {
      ::close(fd);
      throw InputError(path + ": is a directory, not a JSON file");
    }
    if (S_ISREG(st.st_mode) && static_cast<std::uintmax_t>(st.st_size) > kMaxBytes) {
      ::close(fd);
      throw InputError(path + ": file of " + std::to_string(st.st_size) + " bytes is larger than the input limit of " +
                       std::to_string(kMaxBytes) + " bytes");
    }
  }
  std::string text;
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int e = errno;
      ::close(fd);
      throw InputError(path + ": read failed (" + std::strerror(e) + ")");
    }
    if (n == 0) break;
    // JSON text never holds a NUL byte: binary data (or /dev/zero) is refused at once.
    if (std::memchr(buf, '\0', static_cast<std::size_t>(n)) != nullptr) {
      ::close(fd);
      throw InputError(path + ": not JSON: NUL byte at offset " +
                       std::to_string(text.size() + static_cast<std::size_t>(
                                                        static_cast<const char*>(std::memchr(buf, '\0', n)) - buf)));
    }
    text.append(buf, static_cast<std::size_t>(n));
    if (text.size() > kMaxBytes) {
      ::close(fd);
      throw InputError(path + ": input longer than the limit of " + std::to_string(kMaxBytes) + " bytes");
    }
  }
  ::close(fd);
  return text;
}

// A first pass over the text that the DOM cannot do: nesting depth (the DOM's copy,
// dump and comparison recurse, so 100k levels overflow the stack) and duplicate keys
// (nlohmann keeps the last silently; SPEC section 3 calls that bad input).
class StrictSax : public nlohmann::json_sax<Json> {
 public:
  std::string problem;

  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return open(true); }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_array() override { return close(); }
  bool key(string_t& k) override {
    Level& l = stack_.back();
    if (!l.keys.insert(k).second) {
      problem = where() + ": duplicate key " + quote(k);
      return false;
    }
    l.last_key = k;
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    std::string what = e.what();
    const auto pos = what.find("] ");
    if (pos != std::string::npos) what = what.substr(pos + 2);
    problem = "not JSON: " + what;
    return false;
  }

 private:
  struct Level {
    bool object = false;
    std::set<std::string> keys;
    std::string last_key;
    std::size_t items = 0;
  };
  std::vector<Level> stack_;

  bool open(bool object) {
    if (!stack_.empty() && !stack_.back().object) ++stack_.back().items;
    if (stack_.size() >= static_cast<std::size_t>(kMaxDepth)) {
      problem = where() + ": nested deeper than the limit of " + std::to_string(kMaxDepth) + " levels";
      return false;
    }
    stack_.push_back({object, {}, {}, 0});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }
  // The JSON path of the current position, for messages ("solids.\"cup\".profile[2]").
  std::string where() const {
    std::string w;
    for (std::size_t i = 0; i < stack_.size(); ++i) {
      const Level& l = stack_[i];
      const bool inside_more = i + 1 < stack_.size();
      if (i == 6 && stack_.size() > 8) {
        w += "...(" + std::to_string(stack_.size()) + " levels)";
        break;
      }
      if (l.object && !l.last_key.empty()) {
        if (!w.empty()) w += ".";
        const bool plain = std::all_of(l.last_key.begin(), l.last_key.end(), [](unsigned char c) {
          return std::isalnum(c) || c == '_' || c == '-';
        });
        w += plain && !l.last_key.empty() ? l.last_key : quote(l.last_key);
      } else if (!l.object && (inside_more || l.items > 0)) {
        w += "[" + std::to_string(l.items == 0 ? 0 : l.items - 1) + "]";
      }
    }
    return w.empty() ? std::string("top level") : w;
  }
};

}  // namespace

std::string quote(const std::string& s) {
  // JSON-style escapes keep every message on one line whatever a name holds; a name
  // longer than 80 bytes is cut (the message must stay readable).
  std::string out = "\"";
  std::size_t n = 0;
  for (unsigned char c : s) {
    if (++n > 80) {
      out += "...";
      break;
    }
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20 || c == 0x7f) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "\"";
}

Json parse_json_text(const std::string& text, const std::string& path) {
  StrictSax strict;
  if (!Json::sax_parse(text, &strict)) throw InputError(path + ": " + strict.problem);
  try {
    return Json::parse(text);
  } catch (const Json::exception& e) {
    // out_of_range 406 for numbers such as 1e999 that overflow a double (the SAX pass
    // reports them as parse errors too, so this is a second line of defence).
    std::string what = e.what();
    const auto pos = what.find("] ");
    if (pos != std::string::npos) what = what.substr(pos + 2);
    throw InputError(path + ": not JSON: " + what);
  }
}

Json read_json_file(const std::string& path) { return parse_json_text(read_capped(path), path); }

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

void reject_unknown_members(const Json& j, const std::set<std::string>& allowed, const JsonWhere& where) {
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!allowed.count(it.key()) && it.key() != "comment") where.fail("unknown member " + quote(it.key()));
}

}  // namespace revdist
