// `revdist distance CASE [--eps E] [--tol T] [--engine fast|exact] [--json]`:
// the distance of every query of a case (SPEC sections 5 and 6).
#include <chrono>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <unistd.h>
#include <vector>

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
  bool tol_given = false;  // --engine exact defaults to 1e-9 x the query's scale instead
  std::string engine = "fast";
  bool json = false;
};

Json vec_json(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

// One query's answer, whichever engine gave it.
struct Answer {
  Json json;  // the result record of SPEC section 5
  std::vector<std::string> row;
};

std::string yes_no(bool b) { return b ? "yes" : "no"; }

// The fast engine: biarc trees at eps, then the traversal per query.
class FastEngine {
 public:
  FastEngine(const Case& c, const Options& o) : c_(c), model_(build_case_model(c, o.eps)) { opt_.tol = o.tol; }
  Answer query(std::size_t ia, std::size_t ib) const {
    const auto t0 = std::chrono::steady_clock::now();
    const SolidDistanceResult r = solid_distance(model_.instances[ia], model_.instances[ib], opt_);
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    Answer a;
    a.json = {{"a", c_.instances[ia].name},      {"b", c_.instances[ib].name},
              {"lower", r.lower},                {"upper", r.upper},
              {"distance", r.distance},          {"overlap", r.overlap},
              {"converged", r.converged},        {"point_a", vec_json(r.point_a)},
              {"point_b", vec_json(r.point_b)},
              {"stats", {{"node_pairs", r.stats.node_pairs},
                         {"leaf_pairs", r.stats.leaf_pairs},
                         {"patch_pairs", r.stats.patch_pairs},
                         {"quick_pairs", r.stats.quick_pairs},
                         {"refined_parts", r.stats.refined},
                         {"time_us", us}}}};
    if (!r.converged) a.json["reason"] = r.reason;
    a.row = {c_.instances[ia].name, c_.instances[ib].name, full(r.distance), full(r.lower), full(r.upper),
             yes_no(r.overlap), r.converged ? "yes" : "no (" + r.reason + ")", std::to_string(r.stats.node_pairs),
             fixed_digits(us, 4)};
    return a;
  }

 private:
  const Case& c_;
  CaseModel model_;
  DistanceOptions opt_;
};

// The certified engine (exact/solid_distance_exact.h) works on the input
// curves themselves (no biarc trees, so --eps does not apply): lower/upper are
// doubles rounded outward from a proven interval; "converged" means
// upper - lower <= tol, tol = --tol, or 1e-9 x the query's scale when not given.
// stats keeps fast's keys with the exact engine's meaning: node_pairs = parameter
// boxes bounded, leaf_pairs = element pairs (profile element of a x of b),
// patch_pairs = element pairs searched by branch and bound, quick_pairs =
// element pairs settled in closed form (tube against tube), refined_parts =
// boxes re-bounded on MPFI near contact.
class ExactEngine {
 public:
  ExactEngine(const Case& c, const Options& o) : c_(c), o_(o) {
    if (o.tol_given) xo_.absolute_width = o.tol;
    xo_.relative_width = 1e-9;
  }
  Answer query(std::size_t ia, std::size_t ib) const {
    const Instance& ins_a = c_.instances[ia];
    const Instance& ins_b = c_.instances[ib];
    const Profile pa = profile_at(c_.solids[ins_a.solid], ins_a.time);
    const Profile pb = profile_at(c_.solids[ins_b.solid], ins_b.time);
    ExactSolidOptions xo = xo_;
    // A query running past a second shows its bracket on stderr: plain lines
    // when stderr is not a terminal (logs), one rewritten line when it is.
    const bool tty = isatty(fileno(stderr));
    bool shown = false;
    xo.progress = [&](const ExactProgress& p) {
      std::fprintf(stderr, "%sdistance %s-%s: %.1f s, %ld boxes, [%.17g, %.17g] width %.3g (target %.3g)%s",
                   tty ? "\r" : "", ins_a.name.c_str(), ins_b.name.c_str(), p.seconds, p.boxes, p.lower, p.upper,
                   p.upper - p.lower, p.target_width, tty ? "" : "\n");
      std::fflush(stderr);
      shown = true;
    };
    const ExactSolidResult r = solid_distance_exact(pa, ins_a.pose, pb, ins_b.pose, xo);
    if (shown && tty) std::fprintf(stderr, "\n");
    const double tol = o_.tol_given ? o_.tol : 1e-9 * r.scale;
    const bool converged = r.certified && r.upper - r.lower <= tol;
    const double distance = r.certified ? 0.5 * r.lower + 0.5 * r.upper : r.upper;
    const double us = r.time_ms * 1e3;
    Answer a;
    a.json = {{"a", ins_a.name},
              {"b", ins_b.name},
              {"lower", r.lower},
              {"upper", r.certified ? Json(r.upper) : Json(nullptr)},
              {"distance", distance},
              {"overlap", r.overlap},
              {"converged", converged},
              {"certified", r.certified},
              {"tol", tol},
              {"scale", r.scale},
              {"point_a", vec_json(r.point_a)},
              {"point_b", vec_json(r.point_b)},
              {"stats", {{"node_pairs", r.boxes},
                         {"leaf_pairs", r.element_pairs},
                         {"patch_pairs", r.searched_pairs},
                         {"quick_pairs", r.closed_form_pairs},
                         {"refined_parts", r.mpfi_boxes},
                         {"boxes", r.boxes},
                         {"mpfi_boxes", r.mpfi_boxes},
                         {"closed_form_pairs", r.closed_form_pairs},
                         {"time_us", us}}}};
    if (!r.reason.empty()) a.json["reason"] = r.reason;
    a.row = {ins_a.name, ins_b.name, full(distance), full(r.lower), full(r.upper), yes_no(r.overlap),
             converged ? "yes" : "no (" + r.reason + ")", std::to_string(r.boxes), fixed_digits(us, 4)};
    return a;
  }

 private:
  const Case& c_;
  const Options& o_;
  ExactSolidOptions xo_;
};

template <class Engine>
void answer_all(const Case& c, const Engine& engine, const Options& o, const char* work_column) {
  Json results = Json::array();
  Table table({"a", "b", "distance", "lower", "upper", "overlap", "converged", work_column, "time_us"});
  const auto start = std::chrono::steady_clock::now();
  bool progress_shown = false;
  for (std::size_t q = 0; q < c.queries.size(); ++q) {
    Answer a = engine.query(c.queries[q].first, c.queries[q].second);
    results.push_back(std::move(a.json));
    table.add(std::move(a.row));
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (elapsed > 1.0 && q + 1 < c.queries.size()) {
      std::fprintf(stderr, "\rdistance: %zu/%zu queries", q + 1, c.queries.size());
      progress_shown = true;
    }
  }
  if (progress_shown) std::fprintf(stderr, "\n");
  if (o.json) {
    Json doc{{"format", "revdist-result/1"}, {"engine", o.engine}, {"eps", o.eps}, {"tol", o.tol}, {"results", results}};
    if (o.engine == "exact" && !o.tol_given) {  // 1e-9 x each query's scale; the absolute one is in its "tol"
      doc["tol"] = 1e-9;
      doc["tol_relative_to_scale"] = true;
    }
    std::printf("%s\n", doc.dump(1).c_str());
  } else {
    std::printf("%s", table.str().c_str());
  }
}

void run(const Options& o) {
  if (!(o.eps > 0) || !(o.tol > 0)) throw InputError("--eps and --tol must be positive");
  const Case c = read_case(o.file);
  if (o.engine == "exact") {
    answer_all(c, ExactEngine(c, o), o, "boxes");
  } else {
    answer_all(c, FastEngine(c, o), o, "pairs");
  }
}

}  // namespace

void add_distance_command(CLI::App& app) {
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("distance", "Minimum distance for every query of a revdist/1 case");
  cmd->add_option("CASE", opts->file, "revdist/1 JSON case")->required();
  cmd->add_option("--eps", opts->eps, "biarc approximation bound (proven)")->capture_default_str();
  cmd->add_option("--tol", opts->tol, "stop when upper - lower <= tol (exact engine: default 1e-9 x the query's scale)")
      ->capture_default_str();
  cmd->add_option("--engine", opts->engine, "fast (double) or exact (certified)")
      ->check(CLI::IsMember({"fast", "exact"}));
  cmd->add_flag("--json", opts->json, "machine-readable JSON (revdist-result/1)");
  cmd->callback([opts, cmd] {
    opts->tol_given = cmd->count("--tol") > 0;
    run(*opts);
  });
}

}  // namespace revdist::cli
