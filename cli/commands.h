// The subcommands of `revdist`; each file cmd_NAME.cpp adds one to the app.
#pragma once
#include <CLI/CLI.hpp>

#include <cmath>
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

void add_circles_command(CLI::App& app);
void add_fit_command(CLI::App& app);
void add_distance_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_scene_command(CLI::App& app);
void add_scene_gen_command(CLI::App& app);
void add_stress_command(CLI::App& app);
void add_compare_command(CLI::App& app);

}  // namespace revdist::cli
