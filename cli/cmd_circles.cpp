// `revdist circles FILE [--engine fast|exact|both] [--json]`: circle-pair
// distances, closest points, binormal counts and (fast) every binormal line
// (SPEC sections 4 and 5). The count is of distinct feet on circle b (see
// fast/circle_distance.h); the lines are all of them, several per foot possible.
#include <algorithm>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/output.h"
#include "core/circle_io.h"
#include "exact/circle_distance_exact.h"
#include "fast/circle_distance.h"

namespace revdist::cli {

namespace {

using Json = nlohmann::json;

Json vec_json(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

std::string vec_text(const Vec3& v) {
  return "(" + fixed_digits(v.x(), 6) + ", " + fixed_digits(v.y(), 6) + ", " +
         fixed_digits(v.z(), 6) + ")";
}

const char* status_name(CircleCircleStatus s) {
  return s == CircleCircleStatus::ok ? "ok" : "infinitely_many";
}

const char* status_name(ExactStatus s) {
  switch (s) {
    case ExactStatus::ok: return "ok";
    case ExactStatus::infinitely_many: return "infinitely_many";
    case ExactStatus::not_certified: return "not_certified";
  }
  return "not_certified";
}

struct FastAnswer {
  Circle3Circle3Result result;
  int binormals = 0;  // binormal lines (README), -1 for a continuum
  std::vector<CircleBinormal> lines;  // those lines (empty for a continuum)
  double slack = 0.0;  // rounding allowance of the double engine
};

FastAnswer run_fast(const CirclePair& p) {
  FastAnswer f;
  f.result = circle3_circle3_distance(p.a, p.b);
  // The fast engine is within a few ulps of scale = max(radii, centre
  // distance) (worst measured against exact/: 3.6e-15 x scale, Villarceau
  // pairs); 64 ulps bracket it, as rounding the engine accounts for (SPEC 6).
  const double scale = std::max({p.a.radius, p.b.radius, (p.a.center - p.b.center).norm()});
  f.slack = 64 * std::numeric_limits<double>::epsilon() * scale;
  bool infinite = false;
  f.lines = circle3_circle3_binormals(p.a, p.b, &infinite);
  f.binormals = infinite ? -1 : static_cast<int>(f.lines.size());
  return f;
}

Json lines_json(const std::vector<CircleBinormal>& lines) {
  Json out = Json::array();
  for (const CircleBinormal& l : lines)
    out.push_back({{"point_a", vec_json(l.point_a)}, {"point_b", vec_json(l.point_b)}, {"length", l.distance}});
  return out;
}

// The lines under the table, one per row, so the text output shows them all too.
void print_lines(std::size_t pair, const FastAnswer& f) {
  if (f.binormals < 0) {
    std::printf("  #%zu: infinitely many binormal lines (a continuum)\n", pair);
    return;
  }
  for (std::size_t k = 0; k < f.lines.size(); ++k)
    std::printf("  #%zu line %zu: %s - %s  length %s\n", pair, k, vec_text(f.lines[k].point_a).c_str(),
                vec_text(f.lines[k].point_b).c_str(), full(f.lines[k].distance).c_str());
}

Json fast_json(const FastAnswer& f) {
  return Json{{"distance", f.result.distance},
              {"lower", std::max(0.0, f.result.distance - f.slack)},
              {"upper", f.result.distance + f.slack},
              {"status", status_name(f.result.status)},
              {"point_a", vec_json(f.result.point_a)},
              {"point_b", vec_json(f.result.point_b)},
              {"binormals", f.binormals},
              {"lines", lines_json(f.lines)}};
}

Json exact_json(const ExactCircleResult& e) {
  Json j{{"distance", e.distance},   {"lower", e.lower},
         {"upper", e.upper},         {"decimal", e.decimal},
         {"status", status_name(e.status)}, {"contact", e.contact},
         {"point_a", vec_json(e.point_a)}, {"point_b", vec_json(e.point_b)},
         {"binormals", e.binormals}};
  if (e.status == ExactStatus::not_certified) j["reason"] = e.reason;
  return j;
}

struct Options {
  std::string file;
  std::string engine = "fast";
  bool json = false;
};

void run(const Options& o) {
  const std::vector<CirclePair> pairs = read_circle_pairs(o.file);
  const bool want_fast = o.engine != "exact";
  const bool want_exact = o.engine != "fast";
  // Progress (output.h) when the exact engine runs many pairs (~ms each).
  std::optional<Progress> bar;
  if (want_exact && pairs.size() > 200) bar.emplace("circles", pairs.size());

  Json results = Json::array();
  std::vector<FastAnswer> fast_answers;  // for the line listing under the table
  Table table(o.engine == "both"
                  ? std::vector<std::string>{"#", "fast", "exact [lower, upper]", "difference", "fast status",
                                             "exact status", "binormals fast/exact"}
              : want_exact
                  ? std::vector<std::string>{"#", "distance", "[lower, upper]", "status", "binormals", "point_a", "point_b"}
                  : std::vector<std::string>{"#", "distance", "status", "binormals", "point_a", "point_b"});
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (bar) bar->update(i);
    const std::string idx = std::to_string(i);
    if (o.engine == "both") {
      const FastAnswer f = run_fast(pairs[i]);
      const ExactCircleResult e = circle3_circle3_distance_exact(pairs[i].a, pairs[i].b);
      // Distance of the fast value from the certified interval (0 inside it).
      const double diff = f.result.distance < e.lower   ? f.result.distance - e.lower
                          : f.result.distance > e.upper ? f.result.distance - e.upper
                                                        : 0.0;
      results.push_back({{"fast", fast_json(f)}, {"exact", exact_json(e)}, {"difference", diff}});
      table.add({idx, full(f.result.distance), "[" + full(e.lower) + ", " + full(e.upper) + "]",
                 fixed_digits(diff, 3), status_name(f.result.status), status_name(e.status),
                 std::to_string(f.binormals) + "/" + std::to_string(e.binormals)});
      fast_answers.push_back(f);
    } else if (want_fast) {
      const FastAnswer f = run_fast(pairs[i]);
      results.push_back(fast_json(f));
      table.add({idx, full(f.result.distance), status_name(f.result.status),
                 std::to_string(f.binormals), vec_text(f.result.point_a), vec_text(f.result.point_b)});
      fast_answers.push_back(f);
    } else {
      const ExactCircleResult e = circle3_circle3_distance_exact(pairs[i].a, pairs[i].b);
      results.push_back(exact_json(e));
      table.add({idx, full(e.distance), "[" + full(e.lower) + ", " + full(e.upper) + "]",
                 status_name(e.status) + (e.reason.empty() ? std::string() : " (" + e.reason + ")"),
                 std::to_string(e.binormals), vec_text(e.point_a), vec_text(e.point_b)});
    }
  }
  if (bar) bar->finish();

  if (o.json) {
    const Json doc{{"format", "revdist-circles-result/1"}, {"engine", o.engine}, {"results", results}};
    std::printf("%s\n", doc.dump(1).c_str());
  } else {
    std::printf("%s", table.str().c_str());
    if (!fast_answers.empty()) {
      std::printf("binormal lines (fast engine):\n");
      for (std::size_t i = 0; i < fast_answers.size(); ++i) print_lines(i, fast_answers[i]);
    }
  }
}

}  // namespace

void add_circles_command(CLI::App& app) {
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "circles", "Distances between circle pairs of a revdist-circles/1 file: closest points, binormal lines");
  cmd->add_option("FILE", opts->file, "revdist-circles/1 JSON file")->required();
  cmd->add_option("--engine", opts->engine, "fast (double), exact (certified interval) or both")
      ->check(CLI::IsMember({"fast", "exact", "both"}));
  cmd->add_flag("--json", opts->json, "machine-readable JSON (revdist-circles-result/1)");
  cmd->callback([opts] { run(*opts); });
}

}  // namespace revdist::cli
