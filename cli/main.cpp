// revdist: the command-line entry point. Exit status (SPEC section 5):
// 0 success, 2 bad input or usage, 1 internal error.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>

#include "cli/commands.h"
#include "cli/output.h"
#include "core/input_error.h"

namespace {

// The length of the well-formed UTF-8 sequence at p (1 to 4), or 0 when the
// bytes there are not one (a stray continuation, an overlong form, a surrogate).
int utf8_length(const unsigned char* p) {
  const unsigned char c = p[0];
  if (c < 0x80) return 1;
  int n = 0;
  unsigned char lo = 0x80, hi = 0xBF;  // the second byte's range
  if (c >= 0xC2 && c <= 0xDF) n = 2;
  else if (c >= 0xE0 && c <= 0xEF) n = 3, lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
  else if (c >= 0xF0 && c <= 0xF4) n = 4, lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
  else return 0;
  if (p[1] < lo || p[1] > hi) return 0;
  for (int i = 2; i < n; ++i)
    if (p[i] < 0x80 || p[i] > 0xBF) return 0;
  return n;
}

// Every message is one line of UTF-8 whatever the input put into it (file
// names, keys, bytes of a corrupt file): control characters and the Unicode
// line breaks NEL (U+0085), LS and PS (U+2028, U+2029) escaped, bytes that are
// not UTF-8 written as \xNN, and at most 2000 bytes (a 100,000-digit number
// was echoed whole).
std::string one_line(const char* what) {
  constexpr std::size_t kMax = 2000;
  std::string s;
  for (const char* p = what; *p && s.size() < kMax; ++p) {
    const unsigned char c = static_cast<unsigned char>(*p);
    const unsigned char c1 = static_cast<unsigned char>(p[1]);
    if (c == '\n') s += "\\n";
    else if (c == '\r') s += "\\r";
    else if (c < 0x20 || c == 0x7f) s += ' ';
    else if (c == 0xC2 && c1 == 0x85) s += "\\u0085", ++p;
    else if (c == 0xE2 && c1 == 0x80 && (static_cast<unsigned char>(p[2]) | 1) == 0xA9)
      s += p[2] == '\xA8' ? "\\u2028" : "\\u2029", p += 2;
    else if (const int n = utf8_length(reinterpret_cast<const unsigned char*>(p)); n == 0) {
      static const char* hex = "0123456789ABCDEF";
      s += "\\x";
      s += hex[c >> 4];
      s += hex[c & 15];
    } else {
      s.append(p, n);
      p += n - 1;
    }
  }
  if (s.size() >= kMax) s += "...";
  return s;
}

// stdout is checked once everything is written: `> /dev/full` or a closed pipe is an
// error (exit 1), never a silent success.
int finish_stdout(int status) {
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    if (status == 0) {
      std::fprintf(stderr, "revdist: error writing standard output\n");
      return 1;
    }
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"revdist: minimum distance between solids of revolution, fast and provably right"};
  app.require_subcommand(1);
  revdist::cli::add_circles_command(app);
  revdist::cli::add_fit_command(app);
  revdist::cli::add_distance_command(app);
  revdist::cli::add_bench_command(app);
  revdist::cli::add_scene_command(app);
  revdist::cli::add_scene_gen_command(app);
  revdist::cli::add_stress_command(app);
  revdist::cli::add_compare_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, as every other error (CLI11 adds a second, "Run with --help").
    std::fprintf(stderr, "revdist: %s (see revdist --help)\n", one_line(e.what()).c_str());
    return 2;
  } catch (const revdist::InputError& e) {
    std::fprintf(stderr, "revdist: %s\n", one_line(e.what()).c_str());
    return finish_stdout(2);
  } catch (const revdist::cli::RunError& e) {
    std::fprintf(stderr, "revdist: %s\n", one_line(e.what()).c_str());
    return finish_stdout(1);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "revdist: internal error: %s\n", one_line(e.what()).c_str());
    return finish_stdout(1);
  }
  return finish_stdout(0);
}
