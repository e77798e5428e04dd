// `revdist stress --family NAME|all --n N --seed S [--json] [--save-worst DIR] [--shard K/M]`
// and `revdist stress --merge FILES...` (SPEC section 5): argument parsing and
// printing of compare/stress.h.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/output.h"
#include "compare/stress.h"
#include "core/input_error.h"
#include "core/json_util.h"

namespace revdist::cli {

namespace {

using Json = nlohmann::json;

struct Options {
  std::vector<std::string> families;
  long n = 100;
  std::uint64_t seed = 1;
  bool json = false;
  std::string save_worst;
  std::string shard = "1/1";
  std::vector<std::string> merge;
  StressOptions stress;
};

std::vector<std::string> family_names(const std::vector<std::string>& asked) {
  std::vector<std::string> out;
  for (const std::string& a : asked) {
    if (a == "all") {
      for (const FamilyInfo& f : stress_families()) out.push_back(f.name);
      continue;
    }
    bool known = false;
    for (const FamilyInfo& f : stress_families()) known |= f.name == a;
    if (!known) {
      std::string list;
      for (const FamilyInfo& f : stress_families()) list += " " + f.name;
      throw InputError("--family: unknown family \"" + a + "\" (known: all" + list + ")");
    }
    out.push_back(a);
  }
  return out;
}

StressReport read_report(const std::string& path) {
  // The case files' reader: a size limit, no endless device, NUL bytes refused.
  const Json j = read_json_file(path);
  try {
    return stress_from_json(j);
  } catch (const Json::exception& e) {
    throw InputError(path + ": not JSON: " + e.what());
  } catch (const std::runtime_error& e) {
    throw InputError(path + ": " + e.what());
  }
}

void save_worst(const StressReport& r, const std::string& dir) {
  std::filesystem::create_directories(dir);
  for (const FamilyStats& f : r.families) {
    if (f.worst_index < 0) continue;
    const std::string path = dir + "/stress_" + f.name + "_" + std::to_string(f.worst_index) + ".json";
    write_file_atomically(path, f.worst_case.dump(1) + "\n");
  }
  for (const FamilyStats& f : r.families)
    for (const FamilyStats::Unconverged& u : f.unconverged)
      write_file_atomically(dir + "/stress_" + f.name + "_" + std::to_string(u.index) + "_not_converged.json",
                            u.case_json.dump(1) + "\n");
}

void print(const StressReport& r, bool json) {
  if (json) {
    std::printf("%s\n", stress_json(r).dump(1).c_str());
    return;
  }
  Table t({"family", "n", "violations", "nans", "not_conv", "max_abs_error", "max_rel_error", "exact", "uncert",
           "time_s"});
  long n = 0, v = 0, nan = 0, nc = 0, x = 0, xu = 0;
  double ts = 0;
  for (const FamilyStats& f : r.families) {
    t.add({f.name, std::to_string(f.n), std::to_string(f.violations), std::to_string(f.nans),
           std::to_string(f.not_converged), fixed_digits(f.max_abs_error, 3), fixed_digits(f.max_rel_error, 3),
           std::to_string(f.exact_checked), std::to_string(f.exact_uncertified), fixed_digits(f.time_s, 3)});
    n += f.n, v += f.violations, nan += f.nans, nc += f.not_converged, x += f.exact_checked,
        xu += f.exact_uncertified, ts += f.time_s;
  }
  t.add({"total", std::to_string(n), std::to_string(v), std::to_string(nan), std::to_string(nc), "", "",
         std::to_string(x), std::to_string(xu), fixed_digits(ts, 4)});
  std::printf("seed %llu, shard %d/%d, eps %g, tol %g (relative to each case's size)\n%s",
              static_cast<unsigned long long>(r.seed), r.shard_k, r.shard_m, r.options.eps, r.options.tol,
              t.str().c_str());
  for (const FamilyStats& f : r.families)
    if (f.worst_violation) std::printf("worst %s #%ld: %s\n", f.name.c_str(), f.worst_index, f.worst_what.c_str());
  for (const FamilyStats& f : r.families) {
    for (const FamilyStats::Unconverged& u : f.unconverged)
      std::printf("not converged %s #%ld: %s\n", f.name.c_str(), u.index, u.what.c_str());
    if (f.not_converged > static_cast<long>(f.unconverged.size()))
      std::printf("not converged %s: %ld more (the %zu lowest indices are listed)\n", f.name.c_str(),
                  f.not_converged - static_cast<long>(f.unconverged.size()), f.unconverged.size());
  }
}

void run(const Options& o) {
  if (!o.save_worst.empty()) prepare_output_dir(o.save_worst);  // a file there fails now, not after the run
  if (!o.merge.empty()) {
    std::vector<StressReport> shards;
    for (const std::string& path : o.merge) shards.push_back(read_report(path));
    StressReport merged;
    try {
      merged = merge_stress(shards);
    } catch (const std::runtime_error& e) {
      throw InputError(std::string("--merge: ") + e.what());
    }
    if (!o.save_worst.empty()) save_worst(merged, o.save_worst);
    print(merged, o.json);
    return;
  }
  if (o.families.empty()) throw InputError("--family is required (a name or all), or --merge FILES");
  if (o.n < 0) throw InputError("--n must be >= 0");
  int k = 0, m = 0;
  char tail = 0;
  if (std::sscanf(o.shard.c_str(), "%d/%d%c", &k, &m, &tail) != 2 || m < 1 || k < 1 || k > m)
    throw InputError("--shard: expected K/M with 1 <= K <= M, got \"" + o.shard + "\"");
  if (!(o.stress.eps > 0) || !(o.stress.tol > 0)) throw InputError("--eps and --tol must be positive");
  const std::vector<std::string> names = family_names(o.families);
  // Progress (output.h): a rewritten line on a terminal, plain lines every 10 s elsewhere.
  std::optional<Progress> bar;
  auto progress = [&](long done, long total) {
    if (!bar) bar.emplace("stress", static_cast<std::size_t>(total));
    bar->update(static_cast<std::size_t>(done));
  };
  const StressReport r = run_stress(names, o.n, o.seed, k, m, o.stress, StressEngines{}, progress);
  if (bar) bar->finish();
  if (!o.save_worst.empty()) save_worst(r, o.save_worst);
  print(r, o.json);
}

}  // namespace

void add_stress_command(CLI::App& app) {
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "stress", "Near-degenerate families checked against closed forms, a brute force on the true surfaces and exact/");
  cmd->add_option("--family", o->families, "family name, or all (repeatable)");
  cmd->add_option("--n", o->n, "cases per family (at most 10000000)")->check(CLI::Range(0L, 10000000L))->capture_default_str();
  cmd->add_option("--seed", o->seed, "seed of the case stream")
      ->check(seed_number(std::numeric_limits<std::uint64_t>::max()))->capture_default_str();
  cmd->add_flag("--json", o->json, "machine-readable JSON (revdist-stress/1)");
  cmd->add_option("--save-worst", o->save_worst, "write the worst case of each family as a case file into DIR")
      ->check(non_empty_path());
  cmd->add_option("--shard", o->shard, "run slice K of M of the stream (cases with index % M == K - 1)")
      ->capture_default_str();
  cmd->add_option("--merge", o->merge, "combine the JSON of shards into one report")->expected(1, -1);
  cmd->add_option("--eps", o->stress.eps, "fit bound, relative to each case's size")->capture_default_str();
  cmd->add_option("--tol", o->stress.tol, "bracket tolerance, relative to each case's size")->capture_default_str();
  cmd->add_option("--exact-every", o->stress.exact_every, "run exact/ on solid cases with index % K == 0 (0: never)")
      ->check(CLI::Range(0, 1000000000))
      ->capture_default_str();
  cmd->add_option("--exact-budget", o->stress.exact_max_boxes, "exact/ boxes per query before giving up")
      ->check(CLI::Range(1L, 1000000000L))
      ->capture_default_str();
  cmd->add_option("--circle-exact-every", o->stress.circle_exact_every, "the same for circle cases")
      ->check(CLI::Range(0, 1000000000))
      ->capture_default_str();
  cmd->callback([o] { run(*o); });
}

}  // namespace revdist::cli
