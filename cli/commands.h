// The subcommands of `revdist`; each file cmd_NAME.cpp adds one to the app.
#pragma once
#include <CLI/CLI.hpp>

namespace revdist::cli {

void add_circles_command(CLI::App& app);
void add_fit_command(CLI::App& app);
void add_distance_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_scene_command(CLI::App& app);
void add_scene_gen_command(CLI::App& app);
void add_stress_command(CLI::App& app);
void add_compare_command(CLI::App& app);

}  // namespace revdist::cli
