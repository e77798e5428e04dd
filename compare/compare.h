// `revdist compare`: every query of the given cases with fast (each eps x tol),
// exact (certified, once per query) and the FCL mesh baseline (each eps), under
// a few random world frames; CSV + JSON + report.md with SVG plots. Two kinds of
// error are kept apart: end-to-end (against the certified distance of the true
// solids) and arithmetic (fast against exact on the same arc-spline model).
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "compare/stress.h"

namespace revdist {

struct CompareOptions {
  std::vector<double> eps = {1e-3, 1e-4, 1e-5};  // absolute, as `revdist distance`
  std::vector<double> tol = {1e-4, 1e-6, 1e-8};  // absolute
  int repeat = 5;       // timed runs per query and method (median and p90 of thread CPU time)
  int frames = 2;       // random world frames per query besides the case's own (distance unchanged)
  std::uint64_t seed = 1;
  long exact_max_boxes = 2000000;
  double exact_width = 1e-9;  // exact/'s relative width on the true solids
  bool arc_model = true;      // also the arithmetic error on the arc-spline model (exact per eps)
  long model_max_boxes = 200000;
};

struct CompareOutput {
  std::map<std::string, std::string> files;  // name -> content: compare.csv, compare.json, report.md, *.svg
  std::string summary;                       // the headline table, for the terminal
  long bound_violations = 0;                 // fast brackets disjoint from the certified interval
};

// Throws InputError (via read_case) on a bad case file.
// Refuses, with an InputError and before any work, what run_compare could not
// do: a case that does not read, an eps below what doubles resolve for a case
// (core/case_scale.h), or an FCL mesh beyond kMaxMeshTriangles (compare/mesh_fcl.h).
void check_compare(const std::vector<std::string>& cases, const CompareOptions& options);

CompareOutput run_compare(const std::vector<std::string>& cases, const CompareOptions& options,
                          const StressEngines& engines = {}, const std::function<void(const std::string&)>& progress = {});

}  // namespace revdist
