// SVG charts for the compare report (see svg_plot.h).
#include "compare/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace revdist {

namespace {

std::string esc(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else o += c;
  }
  return o;
}

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// A tick label: 10^k on log axes, a short number on linear ones.
std::string tick_label(double v, bool log) {
  if (log) {
    const int k = static_cast<int>(std::lround(std::log10(v)));
    if (k == 0) return "1";
    if (k == 1) return "10";
    return "10<tspan dy=\"-6\" font-size=\"9\">" + std::to_string(k) + "</tspan>";
  }
  return fmt("%g", v);
}

}  // namespace

std::string svg_plot(const PlotSpec& spec) {
  const double W = 860, H = 480, L = 80, R = 300, T = 40, B = 60;
  const double pw = W - L - R, ph = H - T - B;
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  auto ok = [&](double x, double y) {
    return std::isfinite(x) && std::isfinite(y) && (!spec.log_x || x > 0) && (!spec.log_y || y > 0);
  };
  for (const PlotSeries& s : spec.series)
    for (auto [x, y] : s.points)
      if (ok(x, y)) x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  if (!(x0 <= x1)) x0 = 1, x1 = 10, y0 = 1, y1 = 10;
  // Whole decades on log axes; 5% margins on linear ones.
  auto range = [](double& a, double& b, bool log) {
    if (log) {
      a = std::pow(10.0, std::floor(std::log10(a)));
      b = std::pow(10.0, std::ceil(std::log10(b)));
      if (a == b) a /= 10, b *= 10;
    } else {
      const double m = a == b ? std::max(1.0, std::abs(a)) : 0.05 * (b - a);
      a -= m, b += m;
    }
  };
  range(x0, x1, spec.log_x);
  range(y0, y1, spec.log_y);
  auto X = [&](double x) {
    return L + pw * (spec.log_x ? std::log10(x / x0) / std::log10(x1 / x0) : (x - x0) / (x1 - x0));
  };
  auto Y = [&](double y) {
    return T + ph * (1 - (spec.log_y ? std::log10(y / y0) / std::log10(y1 / y0) : (y - y0) / (y1 - y0)));
  };
  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + fmt("%.0f", W) + "\" height=\"" +
                  fmt("%.0f", H) + "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s += "<text x=\"" + fmt("%.0f", L + pw / 2) + "\" y=\"24\" text-anchor=\"middle\" font-size=\"15\" font-weight=\"bold\">" +
       esc(spec.title) + "</text>\n";
  // Grid and ticks.
  auto ticks = [](double a, double b, bool log) {
    std::vector<double> t;
    if (log) {
      const int k0 = static_cast<int>(std::lround(std::log10(a))), k1 = static_cast<int>(std::lround(std::log10(b)));
      const int step = std::max(1, (k1 - k0 + 7) / 8);
      for (int k = k0; k <= k1; k += step) t.push_back(std::pow(10.0, k));
    } else {
      const double raw = (b - a) / 6, mag = std::pow(10.0, std::floor(std::log10(raw)));
      const double st = raw / mag < 2 ? 2 * mag : raw / mag < 5 ? 5 * mag : 10 * mag;
      for (double v = std::ceil(a / st) * st; v <= b + 1e-9 * st; v += st) t.push_back(v);
    }
    return t;
  };
  for (double t : ticks(x0, x1, spec.log_x)) {
    s += "<line x1=\"" + fmt("%.1f", X(t)) + "\" y1=\"" + fmt("%.1f", T) + "\" x2=\"" + fmt("%.1f", X(t)) + "\" y2=\"" +
         fmt("%.1f", T + ph) + "\" stroke=\"#e0e0e0\"/>\n";
    s += "<text x=\"" + fmt("%.1f", X(t)) + "\" y=\"" + fmt("%.1f", T + ph + 18) + "\" text-anchor=\"middle\">" +
         tick_label(t, spec.log_x) + "</text>\n";
  }
  for (double t : ticks(y0, y1, spec.log_y)) {
    s += "<line x1=\"" + fmt("%.1f", L) + "\" y1=\"" + fmt("%.1f", Y(t)) + "\" x2=\"" + fmt("%.1f", L + pw) + "\" y2=\"" +
         fmt("%.1f", Y(t)) + "\" stroke=\"#e0e0e0\"/>\n";
    s += "<text x=\"" + fmt("%.1f", L - 8) + "\" y=\"" + fmt("%.1f", Y(t) + 4) + "\" text-anchor=\"end\">" +
         tick_label(t, spec.log_y) + "</text>\n";
  }
  s += "<rect x=\"" + fmt("%.1f", L) + "\" y=\"" + fmt("%.1f", T) + "\" width=\"" + fmt("%.1f", pw) + "\" height=\"" +
       fmt("%.1f", ph) + "\" fill=\"none\" stroke=\"#333\"/>\n";
  s += "<text x=\"" + fmt("%.1f", L + pw / 2) + "\" y=\"" + fmt("%.1f", H - 22) + "\" text-anchor=\"middle\">" +
       esc(spec.x_label) + "</text>\n";
  s += "<text transform=\"translate(18," + fmt("%.1f", T + ph / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
       esc(spec.y_label) + "</text>\n";
  if (!spec.note.empty())
    s += "<text x=\"" + fmt("%.1f", L) + "\" y=\"" + fmt("%.1f", H - 6) + "\" font-size=\"10\" fill=\"#555\">" +
         esc(spec.note) + "</text>\n";
  // Series, then the legend.
  int row = 0;
  for (const PlotSeries& ser : spec.series) {
    std::string path;
    for (auto [x, y] : ser.points) {
      if (!ok(x, y)) continue;
      if (ser.line) path += (path.empty() ? "M" : " L") + fmt("%.1f", X(x)) + "," + fmt("%.1f", Y(y));
      if (ser.marker > 0)
        s += "<circle cx=\"" + fmt("%.1f", X(x)) + "\" cy=\"" + fmt("%.1f", Y(y)) + "\" r=\"" + fmt("%.1f", ser.marker) +
             "\" fill=\"" + ser.color + "\" fill-opacity=\"0.6\" stroke=\"" + ser.color + "\"/>\n";
    }
    if (!path.empty()) s += "<path d=\"" + path + "\" fill=\"none\" stroke=\"" + ser.color + "\" stroke-width=\"2\"" +
                            (ser.dashed ? " stroke-dasharray=\"6,4\"" : "") + "/>\n";
    const double ly = T + 12 + 18 * row++;
    s += "<rect x=\"" + fmt("%.1f", L + pw + 14) + "\" y=\"" + fmt("%.1f", ly - 8) + "\" width=\"12\" height=\"12\" fill=\"" +
         ser.color + "\"/>\n";
    s += "<text x=\"" + fmt("%.1f", L + pw + 32) + "\" y=\"" + fmt("%.1f", ly + 2) + "\" font-size=\"11\">" +
         esc(ser.name) + "</text>\n";
  }
  s += "</svg>\n";
  return s;
}

}  // namespace revdist
