// The `revdist bench` report: JSON records, a Markdown page and SVG bar charts
// in the manner of the paper's Figures 8, 9 and 12 (section 5).
#pragma once
#include <string>
#include <vector>

#include "compare/bench_paper.h"

namespace revdist {

// revdist-bench/1: run settings and one record per (experiment, pair, eps);
// NaN columns (no FCL side) are null.
std::string bench_json(const BenchResult& r);

// One bar chart: groups along x, one bar per series in each group, optional
// p90 whiskers and a note above each group (the FCL/revdist ratio).
struct BarSeries {
  std::string name, color;
  std::vector<double> values;   // per group; NaN: no bar
  std::vector<double> whisker;  // per group (upper end) or empty
};
struct BarChart {
  std::string title, y_label;
  std::vector<std::string> groups;
  std::vector<BarSeries> series;
  std::vector<std::string> notes;  // per group or empty
  bool log_y = false;
};
// A whole SVG document with the charts stacked vertically (one panel each).
std::string bar_charts_svg(const std::vector<BarChart>& panels, int width = 960, int panel_height = 300);

struct BenchFile {
  std::string name, content;
};
// bench.md, bench.json, fig8.svg, fig9.svg, fig12.svg (the Markdown links the figures).
std::vector<BenchFile> bench_report_files(const BenchResult& r, const std::string& build_info);

}  // namespace revdist
