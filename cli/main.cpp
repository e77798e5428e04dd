// revdist: the command-line entry point. Exit status (SPEC section 5):
// 0 success, 2 bad input or usage, 1 internal error.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "cli/commands.h"
#include "core/input_error.h"

int main(int argc, char** argv) {
  CLI::App app{"revdist: minimum distance between solids of revolution, fast and provably right"};
  app.require_subcommand(1);
  revdist::cli::add_circles_command(app);
  revdist::cli::add_fit_command(app);
  revdist::cli::add_distance_command(app);
  revdist::cli::add_stress_command(app);
  revdist::cli::add_compare_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);  // prints the usage error
    return 2;
  } catch (const revdist::InputError& e) {
    std::fprintf(stderr, "revdist: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "revdist: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
