// `revdist fit CASE [--eps E] [--svg DIR] [--json] [--audit]`: the biarc tree of every
// solid (paper section 4.1, Algorithm 1): pieces, spirals, nodes, leaves,
// bytes, build time and the claimed (lens-proven) error; SVG pictures on
// request (SPEC section 5). `--audit` certifies every leaf with interval
// arithmetic on the input curve (exact/fit_audit.h) and reports the largest
// certified deviation and any leaf whose certificate exceeds its claim.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/output.h"
#include "core/case_io.h"
#include "core/case_scale.h"
#include "core/input_error.h"
#include "exact/fit_audit.h"
#include "fast/biarc_tree.h"
#include "fast/profile_svg.h"

namespace revdist::cli {

namespace {

using Json = nlohmann::json;

struct Options {
  std::string file;
  double eps = 1e-4;
  std::string svg_dir;
  bool json = false;
  bool audit = false;
};

// One solid's fit and its numbers.
struct SolidFit {
  std::string name;
  Profile profile;
  BiarcTree tree;
  BuildStats stats;
  double build_us = 0.0;  // median rebuild time
  std::optional<TreeAudit> audit;  // set by --audit
};

// Median wall time of rebuilding the tree (the deformable hot path), over
// enough repetitions to last ~2 ms (at most 101), after one warm-up build.
double median_build_us(const Profile& profile, double eps, BiarcTree& tree) {
  using Clock = std::chrono::steady_clock;
  std::vector<double> us;
  const auto start = Clock::now();
  while (us.size() < 101 && (us.size() < 5 || Clock::now() - start < std::chrono::milliseconds(2))) {
    const auto t0 = Clock::now();
    rebuild_biarc_tree(profile, eps, tree);
    us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
  }
  std::nth_element(us.begin(), us.begin() + us.size() / 2, us.end());
  return us[us.size() / 2];
}

void run(Options o, bool eps_given) {
  if (eps_given && !(std::isfinite(o.eps) && o.eps > 0))
    throw InputError("--eps must be a finite positive number, got " + fixed_digits(o.eps, 6));
  // An unusable --svg target is bad usage: say so before any work is done.
  NewDirGuard svg_dir(o.svg_dir, !o.svg_dir.empty() && prepare_output_dir(o.svg_dir));
  const Case c = read_case(o.file, false);  // (fit takes no pairs)
  // eps is an absolute length: the default scales with the model, and values below what
  // double rounding resolves are refused (core/case_scale.h).
  const CaseScale scale = case_scale(c);
  if (!eps_given) o.eps = std::max(1e-4 * default_unit(scale), min_eps(scale));
  require_resolvable_eps(o.eps, scale.extent, o.file);
  std::vector<SolidFit> fits;
  for (const SolidDef& solid : c.solids) {
    SolidFit f;
    f.name = solid.name;
    f.profile = profile_at(solid, 0.0);  // deformable solids: keyframe 0
    f.tree = build_biarc_tree(f.profile, o.eps, &f.stats);
    f.build_us = median_build_us(f.profile, o.eps, f.tree);
    fits.push_back(std::move(f));
  }
  if (o.audit) {
    // Tight mode: the certificate measures each fit, not just its claim
    // (~0.7 ms per leaf), so show progress, leaf by leaf (one solid of 200000
    // B-spline spans took 22 s).
    std::vector<std::vector<FitLeaf>> leaves;
    std::size_t total = 0, done = 0;
    for (const SolidFit& f : fits) leaves.push_back(biarc_tree_leaves(f.profile, f.tree)), total += leaves.back().size();
    Progress progress("fit --audit: leaves", total);
    for (std::size_t i = 0; i < fits.size(); ++i) {
      fits[i].audit = audit_leaves(leaves[i], nullptr, true,
                                   [&](std::size_t k) { progress.update(done + k, fits[i].name); });
      done += leaves[i].size();
    }
  }

  if (!o.svg_dir.empty()) {
    std::vector<std::pair<std::string, std::string>> files;
    for (const SolidFit& f : fits)
      files.emplace_back((std::filesystem::path(o.svg_dir) / (file_name_for(f.name) + ".svg")).string(),
                         profile_svg(f.name, f.profile, f.tree));
    write_files_atomically(files);
    svg_dir.keep();
  }

  if (o.json) {
    Json solids = Json::array();
    for (std::size_t i = 0; i < fits.size(); ++i) {
      const SolidFit& f = fits[i];
      Json j{{"name", f.name},
             {"pieces", f.stats.pieces},
             {"spirals", f.stats.spirals},
             {"nodes", f.stats.nodes},
             {"leaves", f.stats.leaves},
             {"bytes", f.stats.bytes},
             {"build_us", f.build_us},
             {"max_error", f.stats.max_error},
             {"max_depth", f.stats.max_depth},
             {"unproven", f.stats.unproven},
             {"deformable", c.solids[i].deformable()}};
      if (f.audit) {
        const TreeAudit& a = *f.audit;
        // null when some leaf could not be certified: no bound is proven then.
        j["certified_error"] = a.certified == a.leaves ? Json(a.max_certified_error) : Json(nullptr);
        j["certified_leaves"] = a.certified;
        j["violations"] = a.violations;
        j["unconfirmed"] = a.unconfirmed;
        j["audit_ms"] = a.time_ms;
        if (!a.first_problem_reason.empty()) j["audit_problem"] = a.first_problem_reason;
      }
      solids.push_back(std::move(j));
    }
    const Json doc{{"format", "revdist-fit/1"}, {"eps", o.eps}, {"solids", solids}};
    std::printf("%s\n", doc.dump(1).c_str());
    return;
  }
  std::vector<std::string> header = {"solid", "pieces", "spirals", "nodes", "leaves", "bytes", "build_us", "max_error"};
  if (o.audit) header.insert(header.end(), {"certified_error", "violations", "unconfirmed"});
  Table table(header);
  for (const SolidFit& f : fits) {
    std::vector<std::string> row = {f.name, std::to_string(f.stats.pieces), std::to_string(f.stats.spirals),
                                    std::to_string(f.stats.nodes), std::to_string(f.stats.leaves),
                                    std::to_string(f.stats.bytes), fixed_digits(f.build_us, 3),
                                    fixed_digits(f.stats.max_error, 3)};
    if (f.audit) {
      const TreeAudit& a = *f.audit;
      row.push_back(a.certified == a.leaves ? fixed_digits(a.max_certified_error, 3)
                                            : "uncertified (" + std::to_string(a.leaves - a.certified) + " leaves)");
      row.push_back(std::to_string(a.violations));
      row.push_back(std::to_string(a.unconfirmed));
    }
    table.add(row);
  }
  std::printf("eps %s (max_error: proven two-sided Hausdorff bound, lens theorem)\n%s",
              fixed_digits(o.eps, 3).c_str(), table.str().c_str());
  for (const SolidFit& f : fits) {
    if (f.stats.unproven > 0) {
      std::fprintf(stderr, "revdist fit: solid \"%s\": %d leaves not proven (spiral hypotheses failed)\n",
                   f.name.c_str(), f.stats.unproven);
    }
  }
}

}  // namespace

void add_fit_command(CLI::App& app) {
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "fit", "Biarc trees of the solids of a case: pieces, spirals, nodes, leaves, bytes, build time, proven error");
  cmd->add_option("CASE", opts->file, "revdist/1 JSON case")->required();
  CLI::Option* eps = cmd->add_option(
      "--eps", opts->eps,
      "biarc error bound (two-sided Hausdorff, proven), an absolute length; default 1e-4, times the largest "
      "profile size when that lies outside [0.01, 100]; at least 1e-12 of the largest solid extent");
  cmd->add_option("--svg", opts->svg_dir,
                  "write DIR/<solid>.svg (profile, arcs, error bands, split points), all files or none; in file "
                  "names every byte but [A-Za-z0-9-] is written _XX")
      ->check(non_empty_path());
  cmd->add_flag("--audit", opts->audit,
                "certify every leaf with interval arithmetic on the input curve (exact/): certified_error, violations");
  cmd->add_flag("--json", opts->json, "machine-readable JSON (revdist-fit/1: solids[] with name, nodes, leaves, "
                                      "bytes, build_us, max_error)");
  cmd->callback([opts, eps] { run(*opts, eps->count() > 0); });
}

}  // namespace revdist::cli
