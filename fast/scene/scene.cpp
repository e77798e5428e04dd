// Scene queries: world boxes from each shape's tree capsules, the broad phase,
// and the narrow phase in deterministic batches over threads.
#include "fast/scene/scene.h"

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <queue>

#include "core/case_io.h"
#include "core/curve_eval.h"
#include "core/input_error.h"
#include "core/profile_check.h"
#include "fast/scene/parallel.h"

namespace revdist {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
using PairKey = std::pair<std::int32_t, std::int32_t>;

// Wall and CPU time of one scene step, added to the stats when it ends; the
// caller's CPU outside parallel_for calls is the step's serial part.
class StepTimer {
 public:
  explicit StepTimer(SceneStats* st)
      : st_(st),
        wall0_(std::chrono::steady_clock::now()),
        cpu0_(thread_cpu_seconds()),
        par0_(thread_parallel_seconds()),
        span0_(thread_span_seconds()) {}
  ~StepTimer() {
    st_->time_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall0_).count();
    const double own = thread_cpu_seconds() - cpu0_;
    const double serial = own - (thread_parallel_seconds() - par0_);
    st_->cpu_ms += 1e3 * own;
    st_->serial_ms += 1e3 * serial;
    st_->span_ms += 1e3 * (serial + thread_span_seconds() - span0_);
  }

 private:
  SceneStats* st_;
  std::chrono::steady_clock::time_point wall0_;
  double cpu0_, par0_, span0_;
};

// A parallel step inside a StepTimer's: run() returns the other workers' CPU seconds.
template <class Run>
void parallel_section(SceneStats* st, Run&& run) {
  st->cpu_ms += 1e3 * run();
}

// Orders answers for k closest: smallest upper first, then instance indices.
bool closer(const ScenePair& x, const ScenePair& y) {
  if (x.result.upper != y.result.upper) return x.result.upper < y.result.upper;
  return x.a != y.a ? x.a < y.a : x.b < y.b;
}

// Leaf pairs of the broad phase in non-decreasing box gap: all pairs of the scene.
class AllPairsStream {
 public:
  explicit AllPairsStream(const AabbTree& t) : t_(t) {
    if (!t.nodes().empty()) q_.push({0.0, 0, 0, true});
  }
  // The next pair with box gap <= limit, if any.
  bool next(double limit, std::int32_t* a, std::int32_t* b) {
    const auto& n = t_.nodes();
    while (!q_.empty() && q_.top().lb <= limit) {
      const Entry e = q_.top();
      q_.pop();
      const auto& na = n[e.x];
      const auto& nb = n[e.y];
      if (e.self) {
        if (na.leaf()) continue;
        q_.push({0.0, na.left, na.left, true});
        q_.push({0.0, na.right, na.right, true});
        push(na.left, na.right);
      } else if (na.leaf() && nb.leaf()) {
        *a = std::min(na.item, nb.item);
        *b = std::max(na.item, nb.item);
        return true;
      } else if (nb.leaf() || (!na.leaf() && na.box.half_area() >= nb.box.half_area())) {
        push(na.left, e.y);
        push(na.right, e.y);
      } else {
        push(e.x, nb.left);
        push(e.x, nb.right);
      }
    }
    return false;
  }

 private:
  struct Entry {
    double lb;
    std::int32_t x, y;
    bool self;  // pairs inside subtree x (then y == x)
    bool operator<(const Entry& o) const { return lb > o.lb; }
  };
  void push(std::int32_t x, std::int32_t y) { q_.push({t_.nodes()[x].box.gap(t_.nodes()[y].box), x, y, false}); }
  const AabbTree& t_;
  std::priority_queue<Entry> q_;
};

// Instances in non-decreasing box gap to instance `query`.
class NeighbourStream {
 public:
  NeighbourStream(const AabbTree& t, const Aabb& box, std::int32_t query) : t_(t), box_(box), query_(query) {
    if (!t.nodes().empty()) q_.push({t.nodes()[0].box.gap(box), 0});
  }
  bool next(double limit, std::int32_t* a, std::int32_t* b) {
    const auto& n = t_.nodes();
    while (!q_.empty() && q_.top().lb <= limit) {
      const Entry e = q_.top();
      q_.pop();
      const auto& nd = n[e.node];
      if (nd.leaf()) {
        if (nd.item == query_) continue;
        *a = query_;
        *b = nd.item;
        return true;
      }
      q_.push({n[nd.left].box.gap(box_), nd.left});
      q_.push({n[nd.right].box.gap(box_), nd.right});
    }
    return false;
  }

 private:
  struct Entry {
    double lb;
    std::int32_t node;
    bool operator<(const Entry& o) const { return lb > o.lb; }
  };
  const AabbTree& t_;
  Aabb box_;
  std::int32_t query_;
  std::priority_queue<Entry> q_;
};

// Sorts pairs (a, b), a < b < n, by (a, b): counting by a (linear), then each
// a's few partners by b (in parallel). Returns the workers' CPU seconds.
double sort_pairs(std::vector<PairKey>* pairs, std::size_t n, int threads) {
  std::vector<std::int32_t> start(n + 1, 0);
  for (const PairKey& p : *pairs) ++start[p.first + 1];
  for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<PairKey> out(pairs->size());
  std::vector<std::int32_t> at(start.begin(), start.end() - 1);
  for (const PairKey& p : *pairs) out[at[p.first]++] = p;
  const double cpu = parallel_for(n, threads, [&](std::size_t i) {
    if (start[i + 1] - start[i] > 1) std::sort(out.begin() + start[i], out.begin() + start[i + 1]);
  });
  pairs->swap(out);
  return cpu;
}

}  // namespace

void SceneStats::add(const SceneStats& o) {
  instances = std::max(instances, o.instances);
  pairs_total += o.pairs_total;
  pairs_tested += o.pairs_tested;
  pairs_culled += o.pairs_culled;
  pairs_threshold += o.pairs_threshold;
  pairs_coherent += o.pairs_coherent;
  narrow_calls += o.narrow_calls;
  node_pairs += o.node_pairs;
  nodes_built += o.nodes_built;
  broad_nodes = std::max(broad_nodes, o.broad_nodes);
  broad_rebuilt = broad_rebuilt || o.broad_rebuilt;
  time_ms += o.time_ms;
  cpu_ms += o.cpu_ms;
  serial_ms += o.serial_ms;
  span_ms += o.span_ms;
}

Scene::Scene(const Case& c, const SceneOptions& options)
    : options_(options), solids_(c.solids), model_(build_case_model(c, options.eps, false, true)) {
  for (const Instance& inst : c.instances) {
    pose0_.push_back(inst.pose);
    motion_.push_back(inst.motion);
    time0_.push_back(inst.time);
  }
  // An instance whose keyframe time runs gets a shape of its own, blended per frame.
  runs_.assign(model_.shapes.size(), 0);
  for (std::size_t i = 0; i < c.instances.size(); ++i) {
    if (motion_[i].time_rate == 0) continue;
    const CaseModel::Shape& shared = *model_.shapes[model_.shape_of[i]];
    auto own = std::make_unique<CaseModel::Shape>();
    own->solid = shared.solid;
    own->time = shared.time;
    own->profile = shared.profile;
    model_.instances[i].profile = &own->profile;
    model_.instances[i].tree = &own->tree;
    model_.shape_of[i] = model_.shapes.size();
    model_.shapes.push_back(std::move(own));
    runs_.push_back(1);
  }
  // No tree is built until a query needs it (build_stale): boxes come from
  // capsules around each shape's control points until then (hull_bounds).
  stale_.assign(model_.shapes.size(), 1);
  bounds_.resize(model_.shapes.size());
  reach_.resize(model_.shapes.size());
  for (std::size_t k = 0; k < model_.shapes.size(); ++k) hull_bounds(k);
  boxes_.resize(size());
  SceneStats ignored;
  set_frame(0.0, &ignored);
}

// Per shape, a frontier of at most 32 tree capsules: tighter boxes than the
// root's capsule alone, and still cheap to move every frame. A lazy tree's
// pending nodes end the frontier (their capsules hold their parts too).
void Scene::fit_bounds(std::size_t shape) {
  const auto& nodes = model_.shapes[shape]->tree.nodes;
  std::vector<std::int32_t> level;
  if (!nodes.empty()) level.push_back(0);
  for (;;) {
    std::vector<std::int32_t> next;
    for (std::int32_t k : level) {
      if (nodes[k].child < 0) next.push_back(k);
      else next.insert(next.end(), {nodes[k].child, nodes[k].child + 1});
    }
    if (next.size() > 32 || next.size() == level.size()) break;
    level = std::move(next);
  }
  std::vector<LocalBound>& b = bounds_[shape];
  b.clear();
  double reach = 0.0;
  for (std::int32_t k : level) {
    b.push_back({nodes[k].seg_a, nodes[k].seg_b, nodes[k].radius});
    reach = std::max({reach, nodes[k].seg_a.norm() + nodes[k].radius, nodes[k].seg_b.norm() + nodes[k].radius});
  }
  reach_[shape] = reach;
}

// The box of a rotated capsule: each end circle (radius |r| about the axis at
// height z) spans |r| sqrt(1 - a_i^2) along world axis i; the cone between
// them lies in the hull of the two circles; the capsule adds its radius.
Aabb Scene::world_box(std::size_t i) const {
  const PosedSolid& s = model_.instances[i];
  const Vec3 axis = s.R.col(2).normalized();
  const Vec3 spread = (Vec3::Ones() - axis.cwiseProduct(axis)).cwiseMax(0.0).cwiseSqrt();
  Aabb box{Vec3::Constant(kInf), Vec3::Constant(-kInf)};
  double size = 0.0;
  for (const LocalBound& c : bounds_[model_.shape_of[i]]) {
    for (const Vec2& p : {c.a, c.b}) {
      const Vec3 centre = s.t + p.y() * axis;
      const Vec3 half = Vec3::Constant(c.radius) + std::abs(p.x()) * spread;
      box.lo = box.lo.cwiseMin(centre - half);
      box.hi = box.hi.cwiseMax(centre + half);
      size = std::max(size, p.norm() + c.radius);
    }
  }
  // Rounding of the pose and of the sums above: a few ulps of the coordinates involved.
  const double margin = 64 * DBL_EPSILON * (s.t.cwiseAbs().maxCoeff() + size);
  box.lo.array() -= margin;
  box.hi.array() += margin;
  return box;
}

void Scene::set_frame(double f, SceneStats* st) {
  StepTimer timer(st);
  st->instances = static_cast<long>(size());
  st->nodes_built += unreported_nodes_;
  unreported_nodes_ = 0;
  // Per instance, independent (a deforming instance has a shape of its own),
  // so spread over the threads in one pass; the results do not depend on their number.
  // A deforming shape is blended here; its tree waits for a query (build_stale).
  parallel_section(st, [&] { return parallel_for(size(), options_.threads, [&](std::size_t i) {
    if (motion_[i].time_rate != 0) {
      CaseModel::Shape& shape = *model_.shapes[model_.shape_of[i]];
      const SolidDef& def = solids_[shape.solid];
      const double t = time_at_frame(time0_[i], motion_[i], f, static_cast<double>(def.keyframes.size() - 1));
      if (t != shape.time) {
        shape.time = t;
        shape.profile = profile_at(def, t);
        hull_bounds(model_.shape_of[i]);
        stale_[model_.shape_of[i]] = 1;
      }
    }
    if (f == 0 || motion_[i].moving()) {  // else the pose is unchanged (the box is recomputed: the shape may not be)
      const Pose p = pose_at_frame(pose0_[i], motion_[i], f);
      model_.instances[i].R = p.rotation();
      model_.instances[i].t = p.translation;
    }
    boxes_[i] = world_box(i);
  }); });
  st->broad_rebuilt = !tree_.refit(boxes_);
  st->broad_nodes = static_cast<long>(tree_.size());
}

// Capsules that hold the profile's curve, from its control points alone (no
// tree): the curve as rational Bezier segments with positive weights, each in
// the convex hull of its control points, so within their largest distance from
// the chord of its ends. Segments are split (or runs of them grouped) into
// about kHullParts parts; a part's sagitta shrinks as the square of its length.
// The boxes of a shape whose tree is not built. (A cylinder around the control
// points, as before, was twice too wide for a bulging Bezier: on a grid of
// 20000 such instances the closest pair took 78902 narrow-phase calls, not 19.)
void Scene::hull_bounds(std::size_t shape) {
  constexpr std::size_t kHullParts = 32;
  std::vector<BezierSegment> segs;
  for (const Piece& piece : model_.shapes[shape]->profile.pieces) {
    std::vector<BezierSegment> s = piece_bezier_segments(piece);
    segs.insert(segs.end(), std::make_move_iterator(s.begin()), std::make_move_iterator(s.end()));
  }
  // Each part: the control points of one or more consecutive segments (sharing ends).
  std::vector<std::vector<Vec2>> parts;
  if (!segs.empty() && segs.size() < kHullParts) {
    const std::size_t m = kHullParts / segs.size();
    for (const BezierSegment& seg : segs) {
      BezierSegment rest = seg;
      for (std::size_t k = m; k > 1; --k) {  // cut off 1/k of what is left: m equal parts
        auto [head, tail] = split_segment(rest, 1.0 / static_cast<double>(k));
        parts.push_back(std::move(head.points));
        rest = std::move(tail);
      }
      parts.push_back(std::move(rest.points));
    }
  } else {
    const std::size_t group = (segs.size() + kHullParts - 1) / kHullParts;
    for (std::size_t g = 0; g < segs.size(); g += group) {
      parts.emplace_back();
      for (std::size_t k = g; k < std::min(segs.size(), g + group); ++k)
        parts.back().insert(parts.back().end(), segs[k].points.begin(), segs[k].points.end());
    }
  }
  std::vector<LocalBound>& b = bounds_[shape];
  b.clear();
  double reach = 0.0, coord = 0.0;
  for (const std::vector<Vec2>& q : parts) {
    for (const Vec2& p : q) coord = std::max(coord, p.cwiseAbs().maxCoeff());
    b.push_back({q.front(), q.back(), chord_flatness(q)});
  }
  // Rounding of the split points and distances: a few ulps of the coordinates.
  const double pad = 64 * DBL_EPSILON * coord;
  for (LocalBound& c : b) {
    c.radius += pad;
    reach = std::max({reach, c.a.norm() + c.radius, c.b.norm() + c.radius});
  }
  reach_[shape] = reach;
}

const PosedSolid& Scene::solid(std::size_t i) const {
  if (const std::size_t k = model_.shape_of[i]; stale_[k]) {
    stale_[k] = 0;
    unreported_nodes_ += build_tree(k);  // reported by the next set_frame
  }
  return model_.instances[i];
}

long Scene::build_tree(std::size_t k) const {
  CaseModel::Shape& shape = *model_.shapes[k];
  rebuild_biarc_tree(shape.profile, options_.eps, shape.tree, &shape.stats, options_.lazy_trees && runs_[k]);
  return static_cast<long>(shape.tree.nodes.size());
}

// Builds the trees of the stale shapes of `instances` (in parallel: one per
// shape), and gives each shape whose time stands still the tighter bounds of
// its tree for the next frames' boxes. Returns the workers' CPU seconds.
double Scene::build_stale(const std::vector<std::int32_t>& instances, SceneStats* st) {
  std::vector<std::size_t> todo;
  for (std::int32_t i : instances)
    if (const std::size_t k = model_.shape_of[i]; stale_[k]) {
      stale_[k] = 0;
      todo.push_back(k);
    }
  if (todo.empty()) return 0.0;
  std::vector<long> built(todo.size(), 0);
  const double cpu = parallel_for(todo.size(), options_.threads, [&](std::size_t j) { built[j] = build_tree(todo[j]); });
  for (long b : built) st->nodes_built += b;
  for (std::size_t k : todo)
    if (!runs_[k]) fit_bounds(k);
  return cpu;
}

SolidDistanceResult Scene::query(std::int32_t a, std::int32_t b, double threshold) const {
  DistanceOptions o = options_.distance;
  o.threshold = threshold;
  return solid_distance(model_.instances[a], model_.instances[b], o);
}

// A point p of a (|p| <= reach) sits at X_ba p in b's frame. Between the
// remembered relative pose and the current one it moved by at most
// |dR|_F reach + |dt| (Frobenius bounds the spectral norm), so the distance
// is at least the old lower bound minus that; the remembered witness points,
// genuine surface points, at the current poses give an upper bound.
bool Scene::settle_from_memory(const PairMemory& m, double d, ScenePair* p) const {
  const PosedSolid& A = model_.instances[m.a];
  const PosedSolid& B = model_.instances[m.b];
  const Mat3 R_ba = B.R.transpose() * A.R;
  const Vec3 t_ba = B.R.transpose() * (A.t - B.t);
  const double reach = reach_[model_.shape_of[m.a]];
  // Rounding of the products above: a few hundred ulps of the coordinates involved.
  const double round = 256 * DBL_EPSILON * (reach + t_ba.norm() + m.t_ba.norm() + reach_[model_.shape_of[m.b]]);
  const double moved = (R_ba - m.R_ba).norm() * reach + (t_ba - m.t_ba).norm() + round;
  const double lower = std::max(0.0, m.lower - moved);
  const Vec3 x = A.R * m.p_a + A.t, y = B.R * m.p_b + B.t;
  const double upper = (x - y).norm();
  if (!(upper <= d || lower > d)) return false;
  // The slot may hold an older answer: every field is set (the reason keeps its storage).
  SolidDistanceResult& r = p->result;
  r.overlap = false;
  r.stats = DistanceStats{};
  r.lower = std::min(lower, upper);
  r.upper = upper;
  r.distance = 0.5 * (r.lower + r.upper);
  r.point_a = x;
  r.point_b = y;
  r.decided = true;
  r.converged = upper - r.lower <= options_.distance.tol;
  r.reason = "settled from the previous frame";
  return true;
}

std::vector<ScenePair> Scene::within(double d, SceneStats* st) {
  std::vector<ScenePair> out;
  within(d, st, &out);
  return out;
}

// Serial work here is what two cores cannot share (SceneStats::serial_ms), so
// every pass over the candidates runs in parallel: the memory lookup, the
// counters (per worker) and the gathering of the answer; the pairs are
// computed in slots kept across calls (their strings keep their storage), and
// moved to the caller's vector, whose elements are reused when it is passed again.
bool Scene::within(double d, SceneStats* st, std::vector<ScenePair>* out, std::size_t max_answers) {
  StepTimer timer(st);
  const long n = static_cast<long>(size());
  std::vector<std::pair<std::int32_t, std::int32_t>>& cand = cand_;
  cand.clear();
  bool over = false;
  parallel_section(st, [&] { return tree_.pairs_within(d, &cand, options_.threads, kMaxWithinPairs, &over); });
  if (over) {
    char dist[32];
    std::snprintf(dist, sizeof dist, "%.6g", d);
    throw InputError(std::string("within ") + dist + ": more than " + std::to_string(kMaxWithinPairs) +
                     " pairs of instances whose boxes are that close (a call answers at most that many); ask a "
                     "smaller distance, or --closest K");
  }
  if (cand.size() > max_answers) {
    // A point of each surface: its profile's start, at azimuth 0.
    auto surface_point = [&](std::int32_t i) {
      const PosedSolid& s = model_.instances[i];
      const Vec2 q = s.profile->pieces.front().start();
      return Vec3(s.R * Vec3(q.x(), 0, q.y()) + s.t);
    };
    std::size_t sure = 0;
    for (const auto& [a, b] : cand) sure += (surface_point(a) - surface_point(b)).norm() <= d;
    if (sure > max_answers) {
      out->clear();
      return false;
    }
  }
  parallel_section(st, [&] { return sort_pairs(&cand, size(), options_.threads); });
  {
    std::vector<std::int32_t> touched;
    if (std::find(stale_.begin(), stale_.end(), 1) != stale_.end())
      for (const auto& [a, b] : cand) touched.insert(touched.end(), {a, b});
    parallel_section(st, [&] { return build_stale(touched, st); });
  }
  // Room to grow by a quarter: a frame with a few more candidates than any
  // before would otherwise move every element (serially) to a new array.
  auto fit = [](auto& v, std::size_t size) {
    if (v.capacity() < size) v.reserve(size + size / 4);
    v.resize(size);
  };
  if (slots_.size() < cand.size()) fit(slots_, cand.size());
  // This call's memory, in the storage of the call before last (no reallocation once warmed up).
  std::vector<PairMemory>& memory = memory_next_;
  fit(memory, cand.size());
  keep_.resize(cand.size());
  struct alignas(64) Counts {  // per worker: integer sums, the same in any order
    long coherent = 0, narrow_calls = 0, node_pairs = 0, nodes_built = 0, threshold = 0;
  };
  std::vector<Counts> counts(static_cast<std::size_t>(std::max(1, options_.threads)));
  parallel_section(st, [&] { return parallel_for_workers(cand.size(), options_.threads, [&](std::size_t k, std::size_t w) {
    ScenePair& p = slots_[k];
    p.a = cand[k].first;
    p.b = cand[k].second;
    // The remembered pair, if any (among the few remembered with the same a);
    // a deforming shape's remembered witness points are no longer on its surface.
    const PairMemory* old = nullptr;
    if (options_.coherence && motion_[p.a].time_rate == 0 && motion_[p.b].time_rate == 0 &&
        static_cast<std::size_t>(p.a) + 1 < memory_first_.size())
      for (std::int32_t j = memory_first_[p.a]; j < memory_first_[p.a + 1]; ++j)
        if (memory_keys_[j].second == p.b) {
          if (memory_[j].valid) old = &memory_[j];
          break;
        }
    Counts& c = counts[w];
    if (old && settle_from_memory(*old, d, &p)) {
      ++c.coherent;
      memory[k] = *old;  // keep the reference pose: bounds do not loosen frame by frame
    } else {
      // With coherence, a pair is first asked about d + h: a "farther" answer
      // then holds for the frames its lower bound needs to lose h, where one
      // proven just past d would be asked again next frame. Not settled so
      // (and not proven within d by the way), it is asked about d itself.
      const double h = options_.coherence ? 0.1 * d : 0.0;
      p.result = query(p.a, p.b, d + h);
      ++c.narrow_calls;
      if (h > 0 && !(p.result.lower > d + h) && !(p.result.upper <= d)) {
        const long built = p.result.stats.nodes_built;  // the first call's work counts too
        p.result = query(p.a, p.b, d);
        p.result.stats.nodes_built += built;
        ++c.narrow_calls;
      }
      c.node_pairs += p.result.stats.node_pairs;
      c.nodes_built += p.result.stats.nodes_built;
      if (p.result.decided) ++c.threshold;
      const PosedSolid& A = model_.instances[p.a];
      const PosedSolid& B = model_.instances[p.b];
      PairMemory& m = memory[k];
      m.a = p.a;
      m.b = p.b;
      m.R_ba = B.R.transpose() * A.R;
      m.t_ba = B.R.transpose() * (A.t - B.t);
      m.lower = p.result.lower;
      m.p_a = A.R.transpose() * (p.result.point_a - A.t);
      m.p_b = B.R.transpose() * (p.result.point_b - B.t);
      m.valid = !p.result.overlap && std::isfinite(p.result.upper);
    }
    p.within = p.result.upper <= d;
    keep_[k] = !(p.result.lower > d);
  }); });
  for (const Counts& c : counts) {
    st->pairs_coherent += c.coherent;
    st->narrow_calls += c.narrow_calls;
    st->node_pairs += c.node_pairs;
    st->nodes_built += c.nodes_built;
    st->pairs_threshold += c.threshold;
  }
  // Where each kept pair goes (a prefix count over bytes), then the moves in parallel.
  std::vector<std::int32_t>& at = at_;
  at.resize(cand.size());
  std::int32_t kept = 0;
  for (std::size_t k = 0; k < cand.size(); ++k) {
    at[k] = kept;
    kept += keep_[k];
  }
  fit(*out, static_cast<std::size_t>(kept));
  parallel_section(st, [&] { return parallel_for(cand.size(), options_.threads, [&](std::size_t k) {
    if (keep_[k]) (*out)[at[k]] = std::move(slots_[k]);
  }); });
  st->pairs_total += n * (n - 1) / 2;
  st->pairs_tested += static_cast<long>(cand.size());
  st->pairs_culled += n * (n - 1) / 2 - static_cast<long>(cand.size());
  if (options_.coherence) {
    // memory[k] is cand[k]'s: keep both, and where each a's pairs start (one
    // sequential pass over the small keys, not a search through the big records).
    std::swap(memory_, memory_next_);
    std::swap(memory_keys_, cand_);
    memory_first_.assign(size() + 1, 0);
    std::size_t j = 0;
    for (std::size_t a = 0; a <= size(); ++a) {
      while (j < memory_keys_.size() && static_cast<std::size_t>(memory_keys_[j].first) < a) ++j;
      memory_first_[a] = static_cast<std::int32_t>(j);
    }
  }
  return true;
}

// Best-first over a stream of pairs in non-decreasing box gap. Batches have a
// fixed composition (the first k pairs, then 32 at a time) and the cutoff T
// (the k-th smallest upper so far) changes only between batches, so threads
// change nothing but the time. A pair is asked "lower > T?" first; if not
// settled so, its full bracket is used (computed again without the threshold
// when the predicate stopped early), so every reported bracket is the one a
// plain solid_distance call gives.
template <class Stream>
std::vector<ScenePair> Scene::best_k(Stream& stream, std::size_t k, SceneStats* st) {
  std::vector<ScenePair> best;
  if (k == 0) return best;
  double cutoff = kInf;
  std::size_t batch_size = k;
  std::vector<ScenePair> batch;
  std::vector<char> rerun;
  for (;;) {
    batch.clear();
    std::int32_t a, b;
    while (batch.size() < batch_size && stream.next(cutoff, &a, &b)) {
      batch.emplace_back();
      batch.back().a = a;
      batch.back().b = b;
    }
    if (batch.empty()) break;
    rerun.assign(batch.size(), 0);
    std::vector<std::int32_t> touched;
    for (const ScenePair& p : batch) touched.insert(touched.end(), {p.a, p.b});
    parallel_section(st, [&] { return build_stale(touched, st); });
    const double t = cutoff;
    parallel_section(st, [&] {
      return parallel_for(batch.size(), options_.threads, [&](std::size_t i) {
        ScenePair& p = batch[i];
        p.result = query(p.a, p.b, std::isfinite(t) ? t : kNaN);
        if (p.result.decided && !(p.result.lower > t)) {
          const long built = p.result.stats.nodes_built;  // the first call's work counts too
          p.result = query(p.a, p.b, kNaN);
          p.result.stats.nodes_built += built;
          rerun[i] = 1;
        }
      });
    });
    for (std::size_t i = 0; i < batch.size(); ++i) {
      ScenePair& p = batch[i];
      ++st->pairs_tested;
      st->narrow_calls += 1 + rerun[i];
      st->node_pairs += p.result.stats.node_pairs;
      st->nodes_built += p.result.stats.nodes_built;
      if (p.result.decided && p.result.lower > t) {
        ++st->pairs_threshold;
        continue;
      }
      p.within = true;
      best.insert(std::upper_bound(best.begin(), best.end(), p, closer), std::move(p));
      if (best.size() > k) best.pop_back();
    }
    if (best.size() == k) cutoff = best.back().result.upper;
    batch_size = 32;
  }
  for (ScenePair& p : best) p.within = false;  // `within` belongs to within(d)
  return best;
}

std::vector<ScenePair> Scene::closest(std::size_t k, SceneStats* st) {
  const long tested0 = st->pairs_tested;
  std::vector<ScenePair> out;
  {
    StepTimer timer(st);
    AllPairsStream stream(tree_);
    out = best_k(stream, k, st);
  }
  const long n = static_cast<long>(size());
  st->pairs_total += n * (n - 1) / 2;
  st->pairs_culled += n * (n - 1) / 2 - (st->pairs_tested - tested0);
  return out;
}

std::vector<ScenePair> Scene::nearest(std::size_t i, std::size_t k, SceneStats* st) {
  const long tested0 = st->pairs_tested;
  std::vector<ScenePair> out;
  {
    StepTimer timer(st);
    NeighbourStream stream(tree_, boxes_[i], static_cast<std::int32_t>(i));
    out = best_k(stream, k, st);
  }
  const long n = static_cast<long>(size());
  st->pairs_total += n - 1;
  st->pairs_culled += n - 1 - (st->pairs_tested - tested0);
  return out;
}

}  // namespace revdist
