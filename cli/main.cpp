// revdist: the command-line entry point. Exit status (SPEC section 5):
// 0 success, 2 bad input or usage, 1 internal error.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>

#include "cli/commands.h"
#include "core/input_error.h"

namespace {

// Every message is one line whatever the input put into it (file names, keys):
// control characters and the Unicode line breaks NEL (U+0085), LS and PS
// (U+2028, U+2029) escaped, and at most 2000 bytes (a 100,000-digit number was
// echoed whole).
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
    else s += *p;
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
  } catch (const std::exception& e) {
    std::fprintf(stderr, "revdist: internal error: %s\n", one_line(e.what()).c_str());
    return finish_stdout(1);
  }
  return finish_stdout(0);
}
