// Small self-contained SVG charts for the compare report: log-log scatter and
// line plots with decade ticks, axis labels and a legend.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace revdist {

struct PlotSeries {
  std::string name;
  std::string color;  // any SVG colour
  std::vector<std::pair<double, double>> points;  // (x, y); non-positive or non-finite points are dropped (log axes)
  bool line = false;    // join the points in order (else markers only)
  double marker = 3.0;  // marker radius in px (0: none)
  bool dashed = false;
};

struct PlotSpec {
  std::string title;
  std::string x_label, y_label;
  bool log_x = true, log_y = true;
  std::vector<PlotSeries> series;
  std::string note;  // one line under the chart
};

std::string svg_plot(const PlotSpec& spec);

}  // namespace revdist
