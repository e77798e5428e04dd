// JSON, Markdown and SVG output of `revdist bench` (paper section 5: Tables 1-2,
// Figures 8, 9, 12), built as strings; the CLI writes them whole.
#include "compare/bench_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

namespace revdist {

namespace {

using Json = nlohmann::json;

Json num(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

std::string fmt(const char* f, double v) {
  if (!std::isfinite(v)) return "–";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string eps_label(double eps) { return fmt("%.0e", eps); }

std::string esc(const std::string& s) {
  std::string o;
  for (char c : s) o += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return o;
}

// ~5 round ticks (1, 2, 5 x 10^k) from 0 to at least hi.
std::vector<double> linear_ticks(double hi) {
  if (!(hi > 0)) hi = 1;
  const double raw = hi / 5, p = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw / p <= 1 ? p : raw / p <= 2 ? 2 * p : raw / p <= 5 ? 5 * p : 10 * p;
  std::vector<double> t;
  for (double v = 0; v < hi + 0.5 * step; v += step) t.push_back(v);
  return t;
}

std::string tick_label(double v) {
  if (v == 0) return "0";
  const double a = std::abs(v);
  if (a >= 1e4 || a < 1e-2) return fmt("%.0e", v);
  return fmt("%g", v);
}

void panel_svg(std::string& s, const BarChart& c, int x0, int y0, int W, int H) {
  const int left = 70, right = 150, top = 34, bottom = 70;
  const double pw = W - left - right, ph = H - top - bottom;
  double lo = INFINITY, hi = 0;
  for (const BarSeries& b : c.series) {
    for (double v : b.values)
      if (std::isfinite(v) && v > 0) lo = std::min(lo, v), hi = std::max(hi, v);
    for (double v : b.whisker)
      if (std::isfinite(v) && v > 0) hi = std::max(hi, v);
  }
  if (!(hi > 0)) hi = 1, lo = 0.1;
  std::vector<double> ticks;
  double ymin = 0, ymax;
  if (c.log_y) {
    ymin = std::pow(10.0, std::floor(std::log10(lo)));
    ymax = std::pow(10.0, std::ceil(std::log10(hi * 1.5)));
    for (double v = ymin; v <= ymax * 1.0001; v *= 10) ticks.push_back(v);
  } else {
    ticks = linear_ticks(hi * 1.12);
    ymax = ticks.back();
  }
  auto Y = [&](double v) {
    const double f = c.log_y ? (std::log10(std::max(v, ymin)) - std::log10(ymin)) / (std::log10(ymax) - std::log10(ymin))
                             : v / ymax;
    return y0 + top + ph * (1 - f);
  };
  char buf[512];
  std::snprintf(buf, sizeof buf, "<text x='%d' y='%d' font-size='15' font-weight='bold'>%s</text>\n", x0 + left,
                y0 + 20, esc(c.title).c_str());
  s += buf;
  for (double t : ticks) {
    std::snprintf(buf, sizeof buf,
                  "<line x1='%d' x2='%.1f' y1='%.1f' y2='%.1f' stroke='#ddd'/><text x='%d' y='%.1f' font-size='11' "
                  "text-anchor='end'>%s</text>\n",
                  x0 + left, x0 + left + pw, Y(t), Y(t), x0 + left - 6, Y(t) + 4, tick_label(t).c_str());
    s += buf;
  }
  std::snprintf(buf, sizeof buf,
                "<text transform='translate(%d,%.1f) rotate(-90)' font-size='12' text-anchor='middle'>%s</text>\n",
                x0 + 16, y0 + top + ph / 2, esc(c.y_label).c_str());
  s += buf;
  const std::size_t ng = c.groups.size(), ns = c.series.size();
  const double gw = pw / std::max<std::size_t>(1, ng), bw = 0.8 * gw / std::max<std::size_t>(1, ns);
  const bool value_labels = ng * ns <= 24;
  for (std::size_t g = 0; g < ng; ++g) {
    const double gx = x0 + left + g * gw + 0.1 * gw;
    double top_y = y0 + top + ph;
    for (std::size_t k = 0; k < ns; ++k) {
      const BarSeries& b = c.series[k];
      const double v = g < b.values.size() ? b.values[g] : NAN;
      if (!std::isfinite(v)) continue;
      const double bx = gx + k * bw, by = Y(v);
      std::snprintf(buf, sizeof buf, "<rect x='%.1f' y='%.1f' width='%.1f' height='%.1f' fill='%s'/>\n", bx, by,
                    std::max(0.5, bw - 1), y0 + top + ph - by, b.color.c_str());
      s += buf;
      top_y = std::min(top_y, by);
      if (g < b.whisker.size() && std::isfinite(b.whisker[g]) && b.whisker[g] > v) {
        const double wy = Y(b.whisker[g]), cx = bx + 0.5 * (bw - 1);
        std::snprintf(buf, sizeof buf,
                      "<line x1='%.1f' x2='%.1f' y1='%.1f' y2='%.1f' stroke='#333'/><line x1='%.1f' x2='%.1f' "
                      "y1='%.1f' y2='%.1f' stroke='#333'/>\n",
                      cx, cx, by, wy, cx - 0.25 * bw, cx + 0.25 * bw, wy, wy);
        s += buf;
        top_y = std::min(top_y, wy);
      }
      if (value_labels) {
        std::snprintf(buf, sizeof buf, "<text x='%.1f' y='%.1f' font-size='10' text-anchor='middle'>%s</text>\n",
                      bx + 0.5 * bw, by - 3, fmt(v < 10 ? "%.2g" : "%.0f", v).c_str());
        s += buf;
      }
    }
    if (g < c.notes.size() && !c.notes[g].empty()) {
      std::snprintf(buf, sizeof buf,
                    "<text x='%.1f' y='%.1f' font-size='11' font-weight='bold' text-anchor='middle'>%s</text>\n",
                    gx + 0.4 * gw, top_y - (value_labels ? 14 : 4), esc(c.notes[g]).c_str());
      s += buf;
    }
    std::snprintf(buf, sizeof buf,
                  "<text transform='translate(%.1f,%.1f) rotate(-30)' font-size='11' text-anchor='end'>%s</text>\n",
                  gx + 0.4 * gw, y0 + top + ph + 14, esc(c.groups[g]).c_str());
    s += buf;
  }
  std::snprintf(buf, sizeof buf, "<line x1='%d' x2='%.1f' y1='%.1f' y2='%.1f' stroke='#000'/>\n", x0 + left,
                x0 + left + pw, y0 + top + ph, y0 + top + ph);
  s += buf;
  for (std::size_t k = 0; k < ns; ++k) {
    const double ly = y0 + top + 8 + 18 * k;
    std::snprintf(buf, sizeof buf,
                  "<rect x='%.1f' y='%.1f' width='12' height='12' fill='%s'/><text x='%.1f' y='%.1f' "
                  "font-size='12'>%s</text>\n",
                  x0 + left + pw + 12, ly, c.series[k].color.c_str(), x0 + left + pw + 30, ly + 10,
                  esc(c.series[k].name).c_str());
    s += buf;
  }
}

const char* kEpsColors[] = {"#9ecae1", "#4292c6", "#08519c", "#08306b", "#041a3a"};

std::vector<const BenchRecord*> select(const BenchResult& r, const std::string& exp, double eps) {
  std::vector<const BenchRecord*> out;
  for (const BenchRecord& x : r.records)
    if (x.experiment == exp && x.eps == eps) out.push_back(&x);
  return out;
}

// Every record of an experiment, in run order (the sweep's: coarsest eps first).
std::vector<const BenchRecord*> select_experiment(const BenchResult& r, const std::string& exp) {
  std::vector<const BenchRecord*> out;
  for (const BenchRecord& x : r.records)
    if (x.experiment == exp) out.push_back(&x);
  return out;
}

const BenchRecord* find(const BenchResult& r, const std::string& exp, const std::string& pair, double eps) {
  for (const BenchRecord& x : r.records)
    if (x.experiment == exp && x.pair == pair && x.eps == eps) return &x;
  return nullptr;
}

std::vector<std::string> pairs_of(const BenchResult& r, const std::string& exp) {
  std::vector<std::string> out;
  for (const BenchRecord& x : r.records)
    if (x.experiment == exp && x.pair != "all" && std::find(out.begin(), out.end(), x.pair) == out.end())
      out.push_back(x.pair);
  return out;
}

// One chart of a per-eps quantity over the pairs of an experiment (Figures 8, 9).
BarChart eps_chart(const BenchResult& r, const std::string& exp, const std::string& title, const std::string& y,
                   double BenchRecord::*field) {
  BarChart c;
  c.title = title, c.y_label = y, c.groups = pairs_of(r, exp);
  for (std::size_t e = 0; e < r.options.eps.size(); ++e) {
    BarSeries s;
    s.name = "eps " + eps_label(r.options.eps[e]);
    s.color = kEpsColors[std::min<std::size_t>(e, 4)];
    for (const std::string& p : c.groups) {
      const BenchRecord* x = find(r, exp, p, r.options.eps[e]);
      s.values.push_back(x ? x->*field : NAN);
    }
    c.series.push_back(s);
  }
  return c;
}

// Figure 12: per eps, revdist (tol 2 eps) and FCL medians per pair, p90 whiskers, ratio notes.
std::vector<BarChart> fig12_charts(const BenchResult& r) {
  std::vector<BarChart> out;
  for (double eps : r.options.eps) {
    BarChart c;
    c.title = "Figure 12, eps " + eps_label(eps) + ": query time in near-contact motion (median, p90 whisker; "
              "bold: FCL / revdist)";
    c.y_label = "thread CPU us (log)";
    c.log_y = true;
    c.groups = pairs_of(r, "motion");
    c.groups.push_back("all");
    BarSeries rv{"revdist tol 2eps", "#1f77b4", {}, {}}, pr{"revdist tol 1e-6", "#7fb8e0", {}, {}},
        fc{"FCL OBBRSS mesh", "#d62728", {}, {}};
    for (const std::string& p : c.groups) {
      const BenchRecord* x = find(r, "motion", p, eps);
      rv.values.push_back(x ? x->median_us : NAN), rv.whisker.push_back(x ? x->p90_us : NAN);
      pr.values.push_back(x ? x->proven_median_us : NAN), pr.whisker.push_back(x ? x->proven_p90_us : NAN);
      fc.values.push_back(x ? x->fcl_median_us : NAN), fc.whisker.push_back(x ? x->fcl_p90_us : NAN);
      c.notes.push_back(x && std::isfinite(x->ratio) ? fmt(x->ratio < 10 ? "%.2gx" : "%.0fx", x->ratio) : "");
    }
    c.series = {rv, pr, fc};
    out.push_back(c);
  }
  return out;
}

// The paper's Tables 1-2 ("Ours" and PQP at eps 1e-3, 1e-4, 1e-5), quoted for comparison.
struct PaperRow {
  const char* model;
  double ours_mb[3], pqp_mb[3], ours_nodes[3], pqp_nodes[3];
};
const PaperRow kPaper[] = {
    {"pawn", {0.081, 0.203, 0.527}, {62, 550, 1437}, {103, 211, 479}, {287e3, 2.5e6, 26.5e6}},
    {"cup", {0.096, 0.199, 0.474}, {59, 657, 1294}, {119, 199, 399}, {272e3, 3.0e6, 25.9e6}},
    {"bottle", {0.099, 0.191, 0.506}, {66, 593, 2003}, {123, 187, 411}, {308e3, 2.7e6, 29.2e6}},
    {"table", {0.079, 0.181, 0.415}, {62, 674, 1395}, {95, 179, 335}, {289e3, 3.1e6, 26.3e6}},
    {"lightmil", {0.187, 0.347, 0.776}, {91, 982, 590}, {247, 375, 687}, {424e3, 4.5e6, 42.5e6}},
};
const PaperRow* paper_row(const std::string& model) {
  for (const PaperRow& p : kPaper)
    if (model == p.model) return &p;
  return nullptr;
}
int paper_eps_index(double eps) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(eps - std::pow(10.0, -3 - k)) < 1e-3 * eps) return k;
  return -1;
}

std::string count(double v) {
  if (!std::isfinite(v)) return "–";
  // %.4g keeps 1000M and more in plain digits (%.3g printed "1.44e+03M").
  if (v >= 1e9) return fmt("%.4gG", v / 1e9);
  if (v >= 1e6) return fmt("%.4gM", v / 1e6);
  if (v >= 1e4) return fmt("%.3gK", v / 1e3);
  return fmt("%.0f", v);
}

void tables_md(std::string& md, const BenchResult& r) {
  const bool paper = r.source == "paper";
  md += "## Tables 1-2: tree sizes\n\nrevdist: biarc tree nodes (leaves) and bytes of nodes + fits. FCL: OBBRSS "
        "hierarchy of the inscribed mesh (bounding volumes, triangles, vertices).";
  if (paper) md += " Paper: the published \"Ours\" and PQP columns (PQP is RSS, not FCL's OBBRSS).";
  md += "\n\n| model | eps | nodes (leaves) | bytes | FCL triangles | FCL BV nodes | FCL bytes | FCL / revdist bytes |";
  if (paper) md += " paper nodes | paper bytes | paper PQP nodes | paper PQP bytes |";
  md += "\n|---|---|---|---|---|---|---|---|";
  if (paper) md += "---|---|---|---|";
  md += "\n";
  for (const std::string& m : pairs_of(r, "build")) {
    for (double eps : r.options.eps) {
      const BenchRecord* x = find(r, "build", m, eps);
      if (!x) continue;
      md += "| " + m + " | " + eps_label(eps) + " | " + std::to_string(x->nodes) + " (" + std::to_string(x->leaves) +
            ") | " + count(x->bytes) + " | " + count(x->fcl_triangles) + " | " + count(x->fcl_bv_nodes) + " | " +
            count(x->fcl_bytes) + " | " + fmt("%.0f", x->bytes > 0 ? double(x->fcl_bytes) / x->bytes : NAN) + " |";
      if (paper) {
        const PaperRow* p = paper_row(m);
        const int k = paper_eps_index(eps);
        if (p && k >= 0)
          md += " " + count(p->ours_nodes[k]) + " | " + count(p->ours_mb[k] * 1e6) + " | " + count(p->pqp_nodes[k]) +
                " | " + count(p->pqp_mb[k] * 1e6) + " |";
        else
          md += " | | | |";
      }
      md += "\n";
    }
  }
  md += "\n";
}

void accuracy_md(std::string& md, const BenchResult& r) {
  md += "## Equal accuracy\n\nFCL meshes are inscribed with chordal error E = eps (every vertex on the true "
        "surface, chords within eps/2 in the profile and eps/2 around the axis); revdist answers with tol = 2 eps "
        "(the bracket of two fits at eps), and in its proven mode with tol = " +
        fmt("%g", r.options.proven_tol) + ". Errors are measured against the certified engine "
        "(exact/solid_distance_exact.h, interval width <= " + fmt("%g", 0.1 * *std::min_element(r.options.eps.begin(), r.options.eps.end())) +
        ") on " + std::to_string(r.options.exact_frames) +
        " frames per pair; |answer - certified interval|, max over the sample. A violation is a revdist bracket "
        "that misses the certified interval (must be 0).\n\n"
        "| experiment | eps | certified frames | uncertified | revdist max err | proven-mode max err | FCL max err | violations |\n"
        "|---|---|---|---|---|---|---|---|\n";
  for (const char* exp : {"motion", "deform"}) {
    for (double eps : r.options.eps) {
      int frames = 0, unc = 0, viol = 0;
      double e = 0, ep = 0, ef = 0;
      bool any_fcl = false, any = false;
      for (const BenchRecord* x : select(r, exp, eps)) {
        if (x->pair == "all") continue;
        any = true;
        frames += x->exact_frames, unc += x->exact_uncertified, viol += x->violations;
        e = std::max(e, x->max_err), ep = std::max(ep, x->proven_max_err), ef = std::max(ef, x->fcl_max_err);
        any_fcl |= std::isfinite(x->fcl_median_us);
      }
      if (!any) continue;
      md += std::string("| ") + exp + " | " + eps_label(eps) + " | " + std::to_string(frames) + " | " +
            std::to_string(unc) + " | " + fmt("%.2g", e) + " | " +
            (std::string(exp) == "motion" ? fmt("%.2g", ep) : "–") + " | " + (any_fcl ? fmt("%.2g", ef) : "–") +
            " | " + std::to_string(viol) + " |\n";
    }
  }
  md += "\n";
}

void motion_md(std::string& md, const BenchResult& r) {
  md += "## Figure 12: pairs in continuous near-contact motion\n\n![Figure 12](fig12.svg)\n\n";
  md += "Each pair moves rigidly and smoothly for " + std::to_string(r.options.frames) +
        " frames with the gap held near 1e-2 x size (some frames touching or slightly overlapping); revdist and "
        "FCL time the same frames in the same run. Times are thread CPU microseconds per query. Overlapping: the "
        "frames where the solids overlap or touch, by a reference query (tol 1e-9 x size on the finest trees); "
        "planned: the frames whose gap target is negative (the motion pushes in along one approach, which leaves "
        "some of them apart).\n\n";
  for (double eps : r.options.eps) {
    md += "### eps " + eps_label(eps) + "\n\n| pair | median | p90 | proven median | proven p90 | coherent median | "
          "FCL median | FCL p90 | FCL / revdist | node pairs | leaf pairs | local proofs | enumerations | overlaps proven / "
          "overlapping / planned | p99 on overlapping | coherent p99 on overlapping | FCL zero | p99 on FCL zero | "
          "unconverged |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const BenchRecord* x : select(r, "motion", eps)) {
      md += "| " + (x->pair == "all" ? "**all**" : x->pair) + " | " + fmt("%.4g", x->median_us) + " | " +
            fmt("%.4g", x->p90_us) + " | " + fmt("%.4g", x->proven_median_us) + " | " +
            fmt("%.4g", x->proven_p90_us) + " | " + fmt("%.4g", x->coherent_median_us) + " | " +
            fmt("%.4g", x->fcl_median_us) + " | " + fmt("%.4g", x->fcl_p90_us) + " | " + fmt("%.3g", x->ratio) + " | " +
            fmt("%.1f", x->node_pairs) + " | " +
            fmt("%.1f", x->leaf_pairs) + " | " + fmt("%.1f", x->local_pairs) + " | " + fmt("%.1f", x->patch_pairs) + " | " +
            std::to_string(x->overlaps) +
            " / " + std::to_string(x->overlapping_frames) + " / " + std::to_string(x->planned_overlaps) + " | " +
            fmt("%.4g", x->overlap_p99_us) + " | " +
            fmt("%.4g", x->coherent_overlap_p99_us) + " | " + std::to_string(x->fcl_zero) + " | " + fmt("%.4g", x->fcl_zero_p99_us) + " | " +
            std::to_string(x->unconverged) + " |\n";
    }
    md += "\n";
  }
}

void sweep_md(std::string& md, const BenchResult& r) {
  const std::vector<const BenchRecord*> sw = select_experiment(r, "sweep");
  if (sw.empty()) return;
  md += "## Query time against eps\n\nrevdist alone (an FCL mesh of 1e-7 chordal error would not fit in memory) on "
        "every Figure 12 frame, tol = 2 eps, fits of each eps built for the purpose. Thread CPU microseconds per "
        "query.\n\n| eps | median | p90 | mean | p99 on overlapping | node pairs | leaf pairs | tree nodes (sum) | "
        "unconverged |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const BenchRecord* x : sw)
    md += "| " + eps_label(x->eps) + " | " + fmt("%.4g", x->median_us) + " | " + fmt("%.4g", x->p90_us) + " | " +
          fmt("%.4g", x->mean_us) + " | " + fmt("%.4g", x->overlap_p99_us) + " | " + fmt("%.1f", x->node_pairs) + " | " +
          fmt("%.1f", x->leaf_pairs) + " | " + std::to_string(x->nodes) + " | " + std::to_string(x->unconverged) + " |\n";
  md += "\n";
}

void deform_md(std::string& md, const BenchResult& r) {
  if (pairs_of(r, "deform").empty()) return;
  md += "## Figure 8: queries against the deformable model\n\n![Figure 8](fig8.svg)\n\n"
        "Each static model moves near contact with the deformable model, whose tree is rebuilt at every frame "
        "(rebuild time in Figure 9, not here). No FCL column: its mesh would have to be rebuilt every frame "
        "(Figure 9 table gives that cost).\n\n| pair | eps | mean | median | p90 | node pairs | overlaps | unconverged |\n"
        "|---|---|---|---|---|---|---|---|\n";
  for (const std::string& p : pairs_of(r, "deform"))
    for (double eps : r.options.eps)
      if (const BenchRecord* x = find(r, "deform", p, eps))
        md += "| " + p + " | " + eps_label(eps) + " | " + fmt("%.4g", x->mean_us) + " | " + fmt("%.4g", x->median_us) +
              " | " + fmt("%.4g", x->p90_us) + " | " + fmt("%.1f", x->node_pairs) + " | " +
              std::to_string(x->overlaps) + " | " + std::to_string(x->unconverged) + " |\n";
  md += "\n";
}

void build_md(std::string& md, const BenchResult& r) {
  md += "## Figure 9: build time\n\n![Figure 9](fig9.svg)\n\nStatic models: median of 41 rebuilds into a warm "
        "tree. Deformable model: blend + rebuild at each of its frames (mean, median, p90). FCL: one build of the "
        "inscribed mesh and its OBBRSS hierarchy (for the deformable model, of its first frame: the cost FCL would "
        "pay per frame).\n\n| model | eps | mean | median | p90 | FCL build | FCL / revdist |\n|---|---|---|---|---|---|---|\n";
  for (const std::string& m : pairs_of(r, "build"))
    for (double eps : r.options.eps)
      if (const BenchRecord* x = find(r, "build", m, eps))
        md += "| " + m + " | " + eps_label(eps) + " | " + fmt("%.4g", x->mean_us) + " | " + fmt("%.4g", x->median_us) +
              " | " + fmt("%.4g", x->p90_us) + " | " + fmt("%.4g", x->fcl_median_us) + " | " + fmt("%.3g", x->ratio) +
              " |\n";
  md += "\n";
}

// Issue 9's targets beside what this run measured (finest and coarsest eps of the run).
void targets_md(std::string& md, const BenchResult& r) {
  const double fine = *std::min_element(r.options.eps.begin(), r.options.eps.end());
  const double coarse = *std::max_element(r.options.eps.begin(), r.options.eps.end());
  const BenchRecord* f = find(r, "motion", "all", fine);
  const BenchRecord* c = find(r, "motion", "all", coarse);
  if (!f || !c) return;
  double build = 0;
  for (const BenchRecord* x : select(r, "build", fine)) build = std::max(build, x->mean_us);
  auto row = [&](const std::string& what, const std::string& target, double v, bool met) {
    md += "| " + what + " | " + target + " | " + fmt("%.4g", v) + " | " + (std::isfinite(v) ? (met ? "yes" : "**no**") : "–") + " |\n";
  };
  const std::string at = " (eps " + eps_label(fine) + ")";
  md += "Targets (issue 9), all pairs and frames of Figure 12:\n\n| quantity | target | measured | met |\n|---|---|---|---|\n";
  row("median query us" + at, "<= 10", f->median_us, f->median_us <= 10);
  row("p90 query us" + at, "<= 40", f->p90_us, f->p90_us <= 40);
  row("FCL / revdist medians" + at, ">= 100", f->ratio, f->ratio >= 100);
  // Growth over the sweep (revdist alone, same frames), else over the run's eps.
  const std::vector<const BenchRecord*> sw = select_experiment(r, "sweep");
  const BenchRecord* gc = sw.empty() ? c : sw.front();
  const BenchRecord* gf = sw.empty() ? f : sw.back();
  if (gc != gf) {  // (one eps: no growth to show)
    const std::string span = " eps " + eps_label(gc->eps) + " -> " + eps_label(gf->eps);
    row("median growth" + span, "<= 2", gf->median_us / gc->median_us, gf->median_us / gc->median_us <= 2);
    row("p90 growth" + span, "<= 2", gf->p90_us / gc->p90_us, gf->p90_us / gc->p90_us <= 2);
  }
  row("proven-mode median us" + at, "<= 30", f->proven_median_us, f->proven_median_us <= 30);
  row("p99 us on the " + std::to_string(f->overlapping_frames) + " frames that overlap or touch" + at, "<= 50",
      f->overlap_p99_us, f->overlap_p99_us <= 50);
  row("p99 us on the " + std::to_string(f->overlaps) + " frames revdist proves overlapping" + at, "<= 50",
      f->proven_overlap_p99_us, f->proven_overlap_p99_us <= 50);
  row("p99 us on the " + std::to_string(f->fcl_zero) + " frames FCL finds intersecting" + at, "<= 50",
      f->fcl_zero_p99_us, f->fcl_zero_p99_us <= 50);
  row("slowest mean build / rebuild us" + at, "<= 500", build, build <= 500);
  md += "\n";
}

}  // namespace

std::string bench_json(const BenchResult& r) {
  Json recs = Json::array();
  for (const BenchRecord& x : r.records) {
    recs.push_back(Json{{"experiment", x.experiment},
                        {"pair", x.pair},
                        {"eps", x.eps},
                        {"tol", x.tol},
                        {"samples", x.samples},
                        {"median_us", num(x.median_us)},
                        {"p90_us", num(x.p90_us)},
                        {"mean_us", num(x.mean_us)},
                        {"fcl_median_us", num(x.fcl_median_us)},
                        {"fcl_p90_us", num(x.fcl_p90_us)},
                        {"fcl_mean_us", num(x.fcl_mean_us)},
                        {"ratio", num(x.ratio)},
                        {"proven_median_us", num(x.proven_median_us)},
                        {"proven_p90_us", num(x.proven_p90_us)},
                        {"coherent_median_us", num(x.coherent_median_us)},
                        {"coherent_p90_us", num(x.coherent_p90_us)},
                        {"coherent_overlap_p99_us", num(x.coherent_overlap_p99_us)},
                        {"nodes", x.nodes},
                        {"leaves", x.leaves},
                        {"bytes", x.bytes},
                        {"fcl_triangles", x.fcl_triangles},
                        {"fcl_bv_nodes", x.fcl_bv_nodes},
                        {"fcl_bytes", x.fcl_bytes},
                        {"node_pairs", x.node_pairs},
                        {"leaf_pairs", x.leaf_pairs},
                        {"patch_pairs", x.patch_pairs},
                        {"quick_pairs", x.quick_pairs},
                        {"local_pairs", x.local_pairs},
                        {"refined", x.refined},
                        {"overlaps", x.overlaps},
                        {"planned_overlaps", x.planned_overlaps},
                        {"overlapping_frames", x.overlapping_frames},
                        {"overlap_median_us", num(x.overlap_median_us)},
                        {"overlap_p99_us", num(x.overlap_p99_us)},
                        {"proven_overlap_p99_us", num(x.proven_overlap_p99_us)},
                        {"unconverged", x.unconverged},
                        {"fcl_zero", x.fcl_zero},
                        {"fcl_zero_p99_us", num(x.fcl_zero_p99_us)},
                        {"exact_frames", x.exact_frames},
                        {"exact_uncertified", x.exact_uncertified},
                        {"max_err", x.max_err},
                        {"proven_max_err", x.proven_max_err},
                        {"fcl_max_err", x.fcl_max_err},
                        {"violations", x.violations}});
  }
  const Json doc{{"format", "revdist-bench/1"},
                 {"source", r.source},
                 {"timing", "thread CPU time (CLOCK_THREAD_CPUTIME_ID) per call, microseconds; median and p90 "
                            "(nearest rank) over the frames"},
                 {"frames", r.options.frames},
                 {"eps", r.options.eps},
                 {"tol", "2 eps"},
                 {"proven_tol", r.options.proven_tol},
                 {"exact_frames", r.options.exact_frames},
                 {"seed", r.options.seed},
                 {"cpu_s", r.cpu_s},
                 {"records", recs}};
  return doc.dump(1) + "\n";
}

std::string bar_charts_svg(const std::vector<BarChart>& panels, int width, int panel_height) {
  const int h = panel_height * static_cast<int>(panels.size());
  std::string s = "<svg xmlns='http://www.w3.org/2000/svg' width='" + std::to_string(width) + "' height='" +
                  std::to_string(h) + "' font-family='sans-serif'>\n<rect width='100%' height='100%' fill='white'/>\n";
  for (std::size_t i = 0; i < panels.size(); ++i) panel_svg(s, panels[i], 0, static_cast<int>(i) * panel_height, width, panel_height);
  return s + "</svg>\n";
}

std::vector<BenchFile> bench_report_files(const BenchResult& r, const std::string& build_info) {
  std::vector<BenchFile> out;
  std::string md = "# revdist bench: " + r.source + "\n\n";
  md += "Son, Yoon, Kim, Elber 2020, section 5, on this machine against FCL 0.7 (OBBRSS meshes of the same chordal "
        "error). " + std::to_string(r.options.frames) + " frames per pair; eps " ;
  for (std::size_t i = 0; i < r.options.eps.size(); ++i) md += (i ? ", " : "") + eps_label(r.options.eps[i]);
  md += "; seed " + std::to_string(r.options.seed) + ". **Timings are per-thread CPU time "
        "(CLOCK_THREAD_CPUTIME_ID) of each call, summarised by the median and p90** (the machine is shared; ratios "
        "within one run are what count). Whole run: " + fmt("%.1f", r.cpu_s) + " s of CPU. Build: " + build_info +
        ".\n\n";
  md += "Summary (all pairs of Figure 12, every frame):\n\n| eps | revdist median | p90 | proven-mode median | p90 | "
        "coherent median | p90 | FCL median | p90 | FCL / revdist (medians) |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (double eps : r.options.eps)
    if (const BenchRecord* x = find(r, "motion", "all", eps))
      md += "| " + eps_label(eps) + " | " + fmt("%.4g", x->median_us) + " | " + fmt("%.4g", x->p90_us) + " | " +
            fmt("%.4g", x->proven_median_us) + " | " + fmt("%.4g", x->proven_p90_us) + " | " +
            fmt("%.4g", x->coherent_median_us) + " | " + fmt("%.4g", x->coherent_p90_us) + " | " +
            fmt("%.4g", x->fcl_median_us) + " | " + fmt("%.4g", x->fcl_p90_us) + " | " + fmt("%.3g", x->ratio) + " |\n";
  md += "\nCoherent: the same frames at tol = 2 eps in sequence, each query warm-started from the previous frame's "
        "answer (`WarmStart`: its points as an upper bound, a previous overlap point still inside the other solid as "
        "the proof).\n\n";
  targets_md(md, r);
  accuracy_md(md, r);
  motion_md(md, r);
  sweep_md(md, r);
  deform_md(md, r);
  build_md(md, r);
  tables_md(md, r);
  out.push_back({"bench.md", md});
  out.push_back({"bench.json", bench_json(r)});
  out.push_back({"fig12.svg", bar_charts_svg(fig12_charts(r), 1100, 330)});
  if (!pairs_of(r, "deform").empty())
    out.push_back({"fig8.svg", bar_charts_svg({eps_chart(r, "deform", "Figure 8: mean query time against the deformable model",
                                                         "thread CPU us", &BenchRecord::mean_us)})});
  out.push_back({"fig9.svg", bar_charts_svg({eps_chart(r, "build", "Figure 9: tree build time (deformable: mean rebuild per frame)",
                                                       "thread CPU us", &BenchRecord::mean_us)})});
  return out;
}

}  // namespace revdist
