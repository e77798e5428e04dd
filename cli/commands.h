// The subcommands of `revdist`; each file cmd_NAME.cpp adds one to the app.
#pragma once
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

namespace revdist::cli {

// A numeric option that must be finite and > 0 (positive) or >= 0, checked
// with one readable line (CLI11's PositiveNumber and NonNegativeNumber print
// the largest double in full, 300 digits).
inline CLI::Validator finite_number(bool positive) {
  const char* what = positive ? "a finite positive number" : "a finite number >= 0";
  return CLI::Validator(
      [positive, what](std::string& s) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(s, v) || !std::isfinite(v) || v < 0 || (positive && v == 0))
          return std::string("must be ") + what + ", got " + s;
        return {};
      },
      positive ? "POSITIVE" : "NONNEGATIVE");
}

// A seed: decimal digits only, at most `max` (CLI11's own conversion wrapped
// -1 to 2^64 - 1 and clamped 10^23 to 2^63 - 1, silently).
inline CLI::Validator seed_number(std::uint64_t max) {
  return CLI::Validator(
      [max](std::string& s) -> std::string {
        const std::string range = "must be an integer from 0 to " + std::to_string(max) + ", got " + s;
        if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos) return range;
        errno = 0;
        const unsigned long long v = std::strtoull(s.c_str(), nullptr, 10);
        if (errno == ERANGE || v > max) return range;
        return {};
      },
      "SEED");
}

// A file or directory option: not empty (an empty --svg or --save-worst wrote
// nothing and exited 0).
inline CLI::Validator non_empty_path() {
  return CLI::Validator([](std::string& s) -> std::string { return s.empty() ? "must not be empty" : ""; }, "PATH");
}

void add_circles_command(CLI::App& app);
void add_fit_command(CLI::App& app);
void add_distance_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_scene_command(CLI::App& app);
void add_scene_gen_command(CLI::App& app);
void add_stress_command(CLI::App& app);
void add_compare_command(CLI::App& app);

}  // namespace revdist::cli
