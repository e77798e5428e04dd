// `revdist distance CASE [--eps E] [--tol T] [--engine fast|exact] [--json]`:
// the distance of every query of a case (SPEC sections 5 and 6).
#include <chrono>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/commands.h"
#include "cli/output.h"
#include "core/case_io.h"
#include "core/input_error.h"
#include "exact/solid_distance_exact.h"
#include "fast/case_model.h"
#include "fast/solid_distance.h"

namespace revdist::cli {

namespace {

using Json = nlohmann::json;

struct Options {
  std::string file;
  double eps = 1e-5;
  double tol = 1e-6;
  std::string engine = "fast";
  bool json = false;
};

Json vec_json(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

void run(const Options& o) {
  if (!(o.eps > 0) || !(o.tol > 0))
    throw InputError("--eps and --tol must be positive");
  if (o.engine == "exact") {
    // The certified engine (exact/solid_distance_exact.h) works on the input curves
    // themselves (no biarc trees, so --eps does not apply): lower/upper are doubles
    // rounded outward from a proven interval; "converged" means upper - lower <= tol.
    const Case c = read_case(o.file);
    ExactSolidOptions xo;
    xo.absolute_width = o.tol;
    Json results = Json::array();
    Table table({"a", "b", "distance", "lower", "upper", "overlap", "converged", "boxes", "time_us"});
    const auto start = std::chrono::steady_clock::now();
    bool progress_shown = false;
    for (std::size_t q = 0; q < c.queries.size(); ++q) {
      const auto [ia, ib] = c.queries[q];
      const Instance& ins_a = c.instances[ia];
      const Instance& ins_b = c.instances[ib];
      const Profile pa = profile_at(c.solids[ins_a.solid], ins_a.time);
      const Profile pb = profile_at(c.solids[ins_b.solid], ins_b.time);
      const ExactSolidResult r = solid_distance_exact(pa, ins_a.pose, pb, ins_b.pose, xo);
      const bool converged = r.certified && r.upper - r.lower <= o.tol;
      const double distance = r.certified ? 0.5 * r.lower + 0.5 * r.upper : r.upper;
      const double us = r.time_ms * 1e3;
      Json j{{"a", ins_a.name},
             {"b", ins_b.name},
             {"lower", r.lower},
             {"upper", r.certified ? Json(r.upper) : Json(nullptr)},
             {"distance", distance},
             {"overlap", r.overlap},
             {"converged", converged},
             {"certified", r.certified},
             {"point_a", vec_json(r.point_a)},
             {"point_b", vec_json(r.point_b)},
             {"stats", {{"boxes", r.boxes}, {"time_us", us}}}};
      if (!r.reason.empty()) j["reason"] = r.reason;
      results.push_back(j);
      table.add({ins_a.name, ins_b.name, full(distance), full(r.lower), full(r.upper), r.overlap ? "yes" : "no",
                 converged ? "yes" : "no (" + r.reason + ")", std::to_string(r.boxes), fixed_digits(us, 4)});
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (elapsed > 1.0 && q + 1 < c.queries.size()) {
        std::fprintf(stderr, "\rdistance: %zu/%zu queries", q + 1, c.queries.size());
        progress_shown = true;
      }
    }
    if (progress_shown) std::fprintf(stderr, "\n");
    if (o.json) {
      const Json doc{{"format", "revdist-result/1"}, {"engine", "exact"}, {"eps", o.eps},
                     {"tol", o.tol},                 {"results", results}};
      std::printf("%s\n", doc.dump(1).c_str());
    } else {
      std::printf("%s", table.str().c_str());
    }
    return;
  }
  const Case c = read_case(o.file);
  const CaseModel model = build_case_model(c, o.eps);
  DistanceOptions opt;
  opt.tol = o.tol;

  Json results = Json::array();
  Table table({"a", "b", "distance", "lower", "upper", "overlap", "converged", "pairs", "time_us"});
  const auto start = std::chrono::steady_clock::now();
  bool progress_shown = false;
  for (std::size_t q = 0; q < c.queries.size(); ++q) {
    const auto [ia, ib] = c.queries[q];
    const auto t0 = std::chrono::steady_clock::now();
    const SolidDistanceResult r = solid_distance(model.instances[ia], model.instances[ib], opt);
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    const std::string& na = c.instances[ia].name;
    const std::string& nb = c.instances[ib].name;
    Json j{{"a", na},
           {"b", nb},
           {"lower", r.lower},
           {"upper", r.upper},
           {"distance", r.distance},
           {"overlap", r.overlap},
           {"converged", r.converged},
           {"point_a", vec_json(r.point_a)},
           {"point_b", vec_json(r.point_b)},
           {"stats", {{"node_pairs", r.stats.node_pairs},
                      {"leaf_pairs", r.stats.leaf_pairs},
                      {"patch_pairs", r.stats.patch_pairs},
                      {"refined_parts", r.stats.refined},
                      {"time_us", us}}}};
    if (!r.converged) j["reason"] = r.reason;
    results.push_back(j);
    table.add({na, nb, full(r.distance), full(r.lower), full(r.upper), r.overlap ? "yes" : "no",
               r.converged ? "yes" : "no (" + r.reason + ")", std::to_string(r.stats.node_pairs),
               fixed_digits(us, 4)});
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (elapsed > 1.0 && q + 1 < c.queries.size()) {
      std::fprintf(stderr, "\rdistance: %zu/%zu queries", q + 1, c.queries.size());
      progress_shown = true;
    }
  }
  if (progress_shown) std::fprintf(stderr, "\n");
  if (o.json) {
    const Json doc{{"format", "revdist-result/1"}, {"engine", o.engine}, {"eps", o.eps},
                   {"tol", o.tol},                 {"results", results}};
    std::printf("%s\n", doc.dump(1).c_str());
  } else {
    std::printf("%s", table.str().c_str());
  }
}

}  // namespace

void add_distance_command(CLI::App& app) {
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("distance", "Minimum distance for every query of a revdist/1 case");
  cmd->add_option("CASE", opts->file, "revdist/1 JSON case")->required();
  cmd->add_option("--eps", opts->eps, "biarc approximation bound (proven)")->capture_default_str();
  cmd->add_option("--tol", opts->tol, "stop when upper - lower <= tol")->capture_default_str();
  cmd->add_option("--engine", opts->engine, "fast (double) or exact (certified)")
      ->check(CLI::IsMember({"fast", "exact"}));
  cmd->add_flag("--json", opts->json, "machine-readable JSON (revdist-result/1)");
  cmd->callback([opts] { run(*opts); });
}

}  // namespace revdist::cli
