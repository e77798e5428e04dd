// Drawing a profile and its biarc tree as SVG (see profile_svg.h).
#include "fast/profile_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/curve_eval.h"

namespace revdist {

namespace {

constexpr int kSamplesPerPiece = 400;
constexpr int kSamplesPerArc = 32;
constexpr double kCanvas = 760.0;   // drawing size in pixels (the longer side)
constexpr double kMargin = 20.0;
constexpr double kLegend = 96.0;    // legend height below the drawing
constexpr double kMinBandPx = 5.0;  // thinnest band drawn

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

struct View {
  double rmin, zmax, s;
  double x(const Vec2& p) const { return kMargin + (p.x() - rmin) * s; }
  double y(const Vec2& p) const { return kMargin + (zmax - p.y()) * s; }
  std::string pt(const Vec2& p) const { return num(x(p)) + "," + num(y(p)); }
};

// Points of a polyline, a point repeating the one before (as printed) left out.
struct Points {
  std::string text, last;
  void add(const std::string& p) {
    if (p == last) return;
    text += p + " ";
    last = p;
  }
};

// About one sample per pixel of length, at most kSamplesPerArc (a profile of
// 100,000 tiny pieces wrote a 664 MB SVG at a fixed count).
std::string arc_points(const View& v, const Arc2& a) {
  const int n = std::clamp(static_cast<int>(std::ceil(a.length * v.s)), 1, kSamplesPerArc);
  Points pts;
  for (int i = 0; i <= n; ++i) pts.add(v.pt(a.point(a.length * i / n)));
  return pts.text;
}

}  // namespace

std::string profile_svg(const std::string& title, const Profile& profile, const BiarcTree& tree) {
  // Samples of the input curve, for the picture and its bounding box: about
  // one per pixel of the piece's control polygon (the curve is no longer), at
  // the scale of the control points' box (the drawing's is no coarser), at
  // most kSamplesPerPiece.
  Vec2 lo = profile.pieces.empty() ? Vec2::Zero() : profile.pieces[0].points[0], hi = lo;
  for (const Piece& piece : profile.pieces)
    for (const Vec2& q : piece.points) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const double s0 = kCanvas / std::max({hi.x() - std::min(lo.x(), 0.0), hi.y() - lo.y(), 1e-300});
  std::vector<std::vector<Vec2>> curves;
  double rmin = 0.0, rmax = 0.0, zmin = 0.0, zmax = 0.0;
  bool first = true;
  for (const Piece& piece : profile.pieces) {
    const auto [u0, u1] = piece_domain(piece);
    double len = 0;
    for (std::size_t i = 1; i < piece.points.size(); ++i) len += (piece.points[i] - piece.points[i - 1]).norm();
    const int n = std::clamp(static_cast<int>(std::ceil(len * s0)), 1, kSamplesPerPiece);
    std::vector<Vec2> c;
    for (int i = 0; i <= n; ++i) {
      const Vec2 p = piece_point(piece, u0 + (u1 - u0) * i / n);
      c.push_back(p);
      if (first) {
        rmin = rmax = p.x();
        zmin = zmax = p.y();
        first = false;
      }
      rmin = std::min(rmin, p.x());
      rmax = std::max(rmax, p.x());
      zmin = std::min(zmin, p.y());
      zmax = std::max(zmax, p.y());
    }
    curves.push_back(std::move(c));
  }
  rmin = std::min(rmin, 0.0);  // always show the axis
  const double span = std::max({rmax - rmin, zmax - zmin, 1e-300});
  const View v{rmin, zmax, kCanvas / span};
  const double width = std::max(2 * kMargin + (rmax - rmin) * v.s, 900.0);  // room for the legend
  const double height = 2 * kMargin + (zmax - zmin) * v.s + kLegend;

  // Band width: 2 eps, or the minimum visible width.
  const double band_true_px = 2.0 * tree.max_error * v.s;
  const double band_px = std::max(band_true_px, kMinBandPx);

  std::string svg;
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(width) + "\" height=\"" + num(height) +
         "\" viewBox=\"0 0 " + num(width) + " " + num(height) + "\" font-family=\"sans-serif\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  // The axis.
  svg += "<line x1=\"" + num(v.x(Vec2(0, zmax))) + "\" y1=\"" + num(v.y(Vec2(0, zmax))) + "\" x2=\"" +
         num(v.x(Vec2(0, zmin))) + "\" y2=\"" + num(v.y(Vec2(0, zmin))) +
         "\" stroke=\"#999\" stroke-dasharray=\"6,4\" stroke-width=\"1\"/>\n";

  // Leaves in profile order (depth first).
  std::vector<const BiarcFit*> leaves;
  std::vector<std::int32_t> stack;
  if (!tree.nodes.empty()) stack.push_back(0);
  while (!stack.empty()) {
    const BiarcNode& n = tree.nodes[stack.back()];
    stack.pop_back();
    if (n.leaf()) {
      leaves.push_back(&tree.fits[n.fit]);
    } else {
      stack.push_back(n.child + 1);
      stack.push_back(n.child);
    }
  }

  // Bands under everything else.
  svg += "<g fill=\"none\" stroke=\"#f5c28a\" stroke-opacity=\"0.8\" stroke-linecap=\"butt\" stroke-width=\"" +
         num(band_px) + "\">\n";
  for (const BiarcFit* f : leaves) {
    for (int k = 0; k < f->arcs; ++k) svg += "<polyline points=\"" + arc_points(v, f->arc[k]) + "\"/>\n";
  }
  svg += "</g>\n";
  // The input curve.
  svg += "<g fill=\"none\" stroke=\"black\" stroke-width=\"0.8\">\n";
  for (const auto& c : curves) {
    Points pts;
    for (const Vec2& p : c) pts.add(v.pt(p));
    svg += "<polyline points=\"" + pts.text + "\"/>\n";
  }
  svg += "</g>\n";
  // The arcs, alternating colours (both arcs of one biarc share a hue, lighter second).
  static const char* colours[4] = {"#1f5fbf", "#6fa0e8", "#2e9e3e", "#86d08f"};
  int index = 0;
  for (const BiarcFit* f : leaves) {
    for (int k = 0; k < f->arcs; ++k) {
      svg += "<polyline fill=\"none\" stroke-width=\"1.6\" stroke=\"" + std::string(colours[(index % 2) * 2 + k]) +
             "\" points=\"" + arc_points(v, f->arc[k]) + "\"/>\n";
    }
    ++index;
  }
  // Spiral split points (red dots) and piece joins (squares).
  for (const SpiralSpan& s : tree.spirals) {
    svg += "<circle cx=\"" + num(v.x(s.ends.p0)) + "\" cy=\"" + num(v.y(s.ends.p0)) +
           "\" r=\"3\" fill=\"#d62728\"/>\n";
  }
  for (const Piece& p : profile.pieces) {
    svg += "<rect x=\"" + num(v.x(p.start()) - 4) + "\" y=\"" + num(v.y(p.start()) - 4) +
           "\" width=\"8\" height=\"8\" fill=\"none\" stroke=\"#444\" stroke-width=\"1.2\"/>\n";
  }
  if (!profile.pieces.empty()) {
    const Vec2 e = profile.pieces.back().end();
    svg += "<rect x=\"" + num(v.x(e) - 4) + "\" y=\"" + num(v.y(e) - 4) +
           "\" width=\"8\" height=\"8\" fill=\"none\" stroke=\"#444\" stroke-width=\"1.2\"/>\n";
  }

  // Legend.
  const double ly = height - kLegend + 18;
  char line[512];
  std::snprintf(line, sizeof line, "%s: %zu pieces, %zu spirals, %zu leaves, eps %.3g, max proven error %.3g",
                title.c_str(), profile.pieces.size(), tree.spirals.size(), leaves.size(), tree.eps,
                tree.max_error);
  svg += "<text x=\"" + num(kMargin) + "\" y=\"" + num(ly) + "\" font-size=\"14\">" + escape(line) + "</text>\n";
  svg += "<text x=\"" + num(kMargin) + "\" y=\"" + num(ly + 20) +
         "\" font-size=\"12\">black: input profile; blue/green: biarcs (alternating leaves; lighter = second arc); "
         "red dots: spiral split points; squares: piece joins</text>\n";
  if (band_true_px < kMinBandPx) {
    std::snprintf(line, sizeof line,
                  "orange band: error band 2*eps, EXAGGERATED to %.0f px (true width %.3g px, x%.3g)", band_px,
                  band_true_px, band_true_px > 0 ? band_px / band_true_px : 0.0);
  } else {
    std::snprintf(line, sizeof line, "orange band: error band 2*eps to scale");
  }
  svg += "<text x=\"" + num(kMargin) + "\" y=\"" + num(ly + 40) + "\" font-size=\"12\">" + escape(line) +
         "</text>\n";
  svg += "</svg>\n";
  return svg;
}

}  // namespace revdist
