// `revdist bench paper|CASE [--eps 1e-3,1e-4,1e-5] [--frames N] [--json] [--out DIR] [--poses FILE]`:
// the paper's section 5 experiments against FCL (compare/bench_paper.h); this
// file parses, shows progress and writes the report (compare/bench_report.h).
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/output.h"
#include "compare/bench_paper.h"
#include "compare/bench_report.h"
#include "core/input_error.h"

namespace revdist::cli {

namespace {

struct Options {
  std::string target;
  std::vector<double> eps = {1e-3, 1e-4, 1e-5};
  int frames = 200;
  int exact_frames = 2;
  bool json = false;
  bool no_fcl = false;
  std::string out = "revdist-bench";
  long long seed = -1;
  std::string poses;
};

void run(const Options& o) {
  BenchOptions bo;
  bo.eps = o.eps;
  bo.frames = o.frames;
  bo.exact_frames = o.exact_frames;
  bo.fcl = !o.no_fcl;
  bo.poses_file = o.poses;
  if (o.seed >= 0) {
    bo.seed = static_cast<std::uint64_t>(o.seed);
  } else if (const char* s = std::getenv("REVDIST_SEED")) {
    bo.seed = std::strtoull(s, nullptr, 10);
  }
  // Progress: one updating line on a terminal, plain lines otherwise (logs, CI).
  // The banner comes with the first line: a poses file refused before any
  // work (exit 2) leaves one line on stderr, not the banner and the error.
  const bool tty = isatty(STDERR_FILENO);
  auto banner = std::make_shared<std::string>();
  bo.progress = [tty, banner](const std::string& line) {
    if (!banner->empty()) {
      std::fputs(banner->c_str(), stderr);
      banner->clear();
    }
    if (tty)
      std::fprintf(stderr, "\r\033[Kbench: %s", line.c_str());
    else
      std::fprintf(stderr, "bench: %s\n", line.c_str());
  };
  const BenchInput in = o.target == "paper" ? paper_bench_input(default_models_dir()) : case_bench_input(o.target);
  check_bench(in, bo);
  NewDirGuard out_dir(o.out, prepare_output_dir(o.out));
  *banner = "bench: " + in.source + ", " + std::to_string(bo.frames) + " frames per pair, seed " +
            std::to_string(bo.seed) + " (REVDIST_SEED or --seed to repeat)\n";
  const BenchResult r = run_bench(in, bo);
  if (tty) std::fprintf(stderr, "\n");

  std::string build = REVDIST_BUILD_TYPE;
  build += ", flags: " REVDIST_BUILD_FLAGS;
  const std::vector<BenchFile> files = bench_report_files(r, build);
  std::filesystem::create_directories(o.out);
  for (const BenchFile& f : files) write_file_atomically((std::filesystem::path(o.out) / f.name).string(), f.content);
  out_dir.keep();

  if (o.json) {
    std::printf("%s", bench_json(r).c_str());
  } else {
    Table t({"eps", "pairs", "median_us", "p90_us", "proven_median_us", "fcl_median_us", "fcl_p90_us", "ratio",
             "violations"});
    for (const BenchRecord& x : r.records) {
      if (x.experiment != "motion" || x.pair != "all") continue;
      t.add({fixed_digits(x.eps, 3), std::to_string(x.samples / std::max(1, o.frames)), fixed_digits(x.median_us, 4),
             fixed_digits(x.p90_us, 4), fixed_digits(x.proven_median_us, 4), fixed_digits(x.fcl_median_us, 4),
             fixed_digits(x.fcl_p90_us, 4), fixed_digits(x.ratio, 3), std::to_string(x.violations)});
    }
    std::printf("near-contact motion, every pair and frame (thread CPU time per query; ratio = FCL / revdist "
                "median, same run)\n%s",
                t.str().c_str());
  }
  std::fprintf(stderr, "bench: report in %s/bench.md (%.1f s CPU)\n", o.out.c_str(), r.cpu_s);
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "bench", "The paper's experiments (Tables 1-2, Figures 8, 9, 12) against FCL meshes at equal accuracy; "
               "writes a Markdown report with SVG charts");
  cmd->add_option("TARGET", opts->target, "'paper' (the bundled models) or a revdist/1 case (all pairs of its "
                                          "static solids; keyframed solids play the deformable model)")
      ->required();
  cmd->add_option("--eps", opts->eps, "biarc error bounds, comma separated (FCL meshes use the same chordal error; "
                                      "revdist tol = 2 eps)")
      ->delimiter(',')
      ->check(finite_number(true));
  cmd->add_option("--frames", opts->frames, "frames of near-contact motion per pair (default 200)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--exact-frames", opts->exact_frames,
                  "frames per pair checked against the certified engine (default 2; 0 skips)")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--seed", opts->seed, "motion seed (default REVDIST_SEED or 20200501)")
      ->check(seed_number(static_cast<std::uint64_t>(std::numeric_limits<long long>::max())));
  cmd->add_flag("--no-fcl", opts->no_fcl, "skip the FCL baseline");
  cmd->add_option("--poses", opts->poses,
                  "motion frames file: read when it exists (written by this option for the same target, seed and "
                  "frames), else written; two builds then time the same poses")
      ->check(non_empty_path());
  cmd->add_option("--out", opts->out, "report directory (bench.md, bench.json, fig8/9/12.svg), default revdist-bench")
      ->check(non_empty_path());
  cmd->add_flag("--json", opts->json, "print the revdist-bench/1 records on stdout");
  cmd->callback([opts] { run(*opts); });
}

}  // namespace revdist::cli
