// `revdist compare CASE... [--eps LIST] [--tol LIST] [--out DIR]` (SPEC section
// 5): argument parsing and file writing around compare/compare.h.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/output.h"
#include "compare/compare.h"
#include "core/input_error.h"

namespace revdist::cli {

namespace {

struct Options {
  std::vector<std::string> cases;
  std::vector<double> eps, tol;
  std::string out = "compare_report";
  bool json = false;
  bool no_model = false;
  CompareOptions compare;
};

void run(Options o) {
  if (!o.eps.empty()) o.compare.eps = o.eps;
  if (!o.tol.empty()) o.compare.tol = o.tol;
  for (double e : o.compare.eps)
    if (!(e > 0)) throw InputError("--eps: every value must be positive");
  for (double t : o.compare.tol)
    if (!(t > 0)) throw InputError("--tol: every value must be positive");
  // (Upper limits: a billion frames allocated 3.7 GB before the first query.)
  if (o.compare.repeat < 1 || o.compare.repeat > 1000 || o.compare.frames < 0 || o.compare.frames > 100000)
    throw InputError("--repeat must be in 1..1000 and --frames in 0..100000");
  o.compare.arc_model = !o.no_model;
  check_compare(o.cases, o.compare);  // every case read and every eps checked before any work
  NewDirGuard out_dir(o.out, prepare_output_dir(o.out));
  // Progress: one updating line on a terminal; otherwise (logs, CI) a plain
  // line at most every 10 s.
  bool shown = false;
  const bool tty = isatty(STDERR_FILENO) == 1;
  auto last = std::chrono::steady_clock::now();
  const CompareOutput out = run_compare(o.cases, o.compare, StressEngines{}, [&](const std::string& what) {
    if (tty) {
      std::fprintf(stderr, "\rcompare: %-70.70s", what.c_str());
      shown = true;
    } else if (const auto now = std::chrono::steady_clock::now(); now - last >= std::chrono::seconds(10)) {
      std::fprintf(stderr, "compare: %s\n", what.c_str());
      last = now;
    }
  });
  if (shown) std::fprintf(stderr, "\n");
  std::filesystem::create_directories(o.out);
  for (const auto& [name, content] : out.files) write_file_atomically(o.out + "/" + name, content);
  out_dir.keep();
  if (o.json) {
    std::printf("%s", out.files.at("compare.json").c_str());
  } else {
    std::printf("%s\nfast bound violations: %ld\nwrote %s/report.md, compare.csv, compare.json and %zu SVG plots\n",
                out.summary.c_str(), out.bound_violations, o.out.c_str(), out.files.size() - 3);
  }
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("compare", "fast vs exact vs FCL meshes on every query: CSV, JSON, report.md, SVG");
  cmd->add_option("CASE", o->cases, "revdist/1 cases")->required()->expected(1, -1);
  cmd->add_option("--eps", o->eps, "fit bounds / mesh chordal errors (comma list; default 1e-3,1e-4,1e-5)")
      ->delimiter(',');
  cmd->add_option("--tol", o->tol, "fast tolerances (comma list; default 1e-4,1e-6,1e-8)")->delimiter(',');
  cmd->add_option("--out", o->out, "output directory")->check(non_empty_path())->capture_default_str();
  cmd->add_option("--repeat", o->compare.repeat, "timed runs per query and method")->capture_default_str();
  cmd->add_option("--frames", o->compare.frames, "random world frames per query besides the case's own")
      ->capture_default_str();
  cmd->add_option("--seed", o->compare.seed, "seed of the random frames")
      ->check(seed_number(std::numeric_limits<decltype(o->compare.seed)>::max()))->capture_default_str();
  cmd->add_flag("--no-arc-model", o->no_model, "skip the arithmetic error on the arc-spline model");
  cmd->add_flag("--json", o->json, "print compare.json to stdout");
  cmd->callback([o] { run(*o); });
}

}  // namespace revdist::cli
