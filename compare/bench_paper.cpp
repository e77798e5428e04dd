// `revdist bench`: the paper's section 5 experiments (Tables 1-2, Figures 8, 9,
// 12) with FCL OBBRSS meshes of the same chordal error as the same-run baseline.
#include "compare/bench_paper.h"

#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include <Eigen/Geometry>

#include "compare/mesh_fcl.h"
#include "compare/motion.h"
#include "compare/thread_clock.h"
#include "core/case_io.h"
#include "core/case_scale.h"
#include "core/input_error.h"
#include "core/json_util.h"
#include "exact/solid_distance_exact.h"
#include "fast/biarc_tree.h"
#include "fast/solid_distance.h"

namespace revdist {

namespace {

double mean(const std::vector<double>& v) {
  if (v.empty()) return NAN;
  double s = 0;
  for (double x : v) s += x;
  return s / v.size();
}

std::string eps_label(double eps) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0e", eps);
  return buf;
}

// A solid's tree at one eps (stable address: PosedSolid points into it).
struct Built {
  Profile profile;
  BiarcTree tree;
  BuildStats stats;
  PosedSolid posed() const {
    PosedSolid p;
    p.profile = &profile;
    p.tree = &tree;
    return p;
  }
};

// The deformable solid over the frames: profile and tree per frame at one eps.
struct Morph {
  std::vector<std::unique_ptr<Built>> frames;
  std::vector<double> rebuild_us;  // blend + rebuild per frame
};

double morph_time(const SolidDef& def, int j, int frames) {
  return frames > 1 ? static_cast<double>(def.keyframes.size() - 1) * j / (frames - 1) : 0.0;
}

Morph build_morph(const SolidDef& def, double eps, int frames) {
  Morph m;
  BiarcTree scratch;  // the hot path reuses one tree's storage
  for (int j = 0; j < frames; ++j) {
    auto b = std::make_unique<Built>();
    const double c0 = thread_cpu_us();
    b->profile = profile_at(def, morph_time(def, j, frames));
    rebuild_biarc_tree(b->profile, eps, scratch, &b->stats);
    m.rebuild_us.push_back(thread_cpu_us() - c0);
    b->tree = scratch;
    m.frames.push_back(std::move(b));
  }
  return m;
}

// Median and p90 of rebuilding one tree (after a warm-up build sized the storage).
std::vector<double> time_rebuilds(const Profile& p, double eps, int reps) {
  BiarcTree tree;
  rebuild_biarc_tree(p, eps, tree);
  std::vector<double> us;
  for (int i = 0; i < reps; ++i) {
    const double c0 = thread_cpu_us();
    rebuild_biarc_tree(p, eps, tree);
    us.push_back(thread_cpu_us() - c0);
  }
  return us;
}

struct QueryTimes {
  std::vector<double> us;
  int planned_overlaps = 0;  // frames planned to overlap (gap target < 0)
  std::vector<double> overlap_us;  // frames that overlap (PairMotion::overlapping)
  std::vector<double> proven_overlap_us;  // frames answered as a proven overlap
  std::vector<SolidDistanceResult> sample;  // results at the certified sample frames
  double node_pairs = 0, leaf_pairs = 0, patch_pairs = 0, quick_pairs = 0, local_pairs = 0, refined = 0;
  int overlaps = 0, unconverged = 0;
};

void set_counters(BenchRecord& r, const QueryTimes& q) {
  const double n = std::max<std::size_t>(1, q.us.size());
  r.samples = static_cast<int>(q.us.size());
  r.median_us = nearest_rank_percentile(q.us, 0.5);
  r.p90_us = nearest_rank_percentile(q.us, 0.9);
  r.mean_us = mean(q.us);
  r.node_pairs = q.node_pairs / n, r.leaf_pairs = q.leaf_pairs / n, r.patch_pairs = q.patch_pairs / n;
  r.quick_pairs = q.quick_pairs / n, r.local_pairs = q.local_pairs / n, r.refined = q.refined / n;
  r.overlaps = q.overlaps, r.unconverged = q.unconverged;
  r.planned_overlaps = q.planned_overlaps;
  r.overlapping_frames = static_cast<int>(q.overlap_us.size());
  r.overlap_median_us = nearest_rank_percentile(q.overlap_us, 0.5);
  r.overlap_p99_us = nearest_rank_percentile(q.overlap_us, 0.99);
  r.proven_overlap_p99_us = nearest_rank_percentile(q.proven_overlap_us, 0.99);
}

void set_coherent(BenchRecord& r, const QueryTimes& q) {
  r.coherent_median_us = nearest_rank_percentile(q.us, 0.5);
  r.coherent_p90_us = nearest_rank_percentile(q.us, 0.9);
  r.coherent_overlap_p99_us = nearest_rank_percentile(q.overlap_us, 0.99);
}

// Times solid_distance on every frame, one call per frame, same poses as FCL;
// coherent: each call warm-started from the previous frame's answer.
// overlapping: the frames that overlap (empty: not known).
QueryTimes time_queries(const std::vector<MotionFrame>& frames, const std::function<PosedSolid(int)>& a,
                        const std::function<PosedSolid(int)>& b, double tol, const std::vector<int>& sample,
                        const std::vector<char>& overlapping, bool coherent = false) {
  QueryTimes q;
  DistanceOptions o;
  o.tol = tol;
  std::size_t next = 0;
  WarmStart warm;
  for (int j = 0; j < static_cast<int>(frames.size()); ++j) {
    PosedSolid A = a(j), B = b(j);
    A.R = frames[j].R_WA, A.t = frames[j].t_WA, B.R = frames[j].R_WB, B.t = frames[j].t_WB;
    const double c0 = thread_cpu_us();
    const SolidDistanceResult r = solid_distance(A, B, o, warm);
    if (coherent) warm = warm_start_of(r, A, B);
    q.us.push_back(thread_cpu_us() - c0);
    q.planned_overlaps += frames[j].target < 0;
    if (!overlapping.empty() && overlapping[j]) q.overlap_us.push_back(q.us.back());
    if (r.overlap) q.proven_overlap_us.push_back(q.us.back());
    q.node_pairs += r.stats.node_pairs, q.leaf_pairs += r.stats.leaf_pairs, q.patch_pairs += r.stats.patch_pairs;
    q.quick_pairs += r.stats.quick_pairs, q.local_pairs += r.stats.local_pairs, q.refined += r.stats.refined;
    q.overlaps += r.overlap, q.unconverged += !r.converged;
    if (next < sample.size() && sample[next] == j) q.sample.push_back(r), ++next;
  }
  return q;
}

// Frames checked by the certified engine: the middles of k equal stretches of the
// motion (its first and last frames are nearly the same pose: the motion is periodic).
std::vector<int> sample_frames(int frames, int k) {
  std::vector<int> out;
  k = std::min(k, frames);
  for (int i = 0; i < k; ++i) out.push_back(static_cast<int>((i + 0.5) * frames / k));
  return out;
}

struct Certified {
  bool ok = false;
  double lower = 0, upper = 0;
};

// Error of an answer against the certified interval: 0 inside it.
double error_vs(const Certified& c, double d) { return d < c.lower ? c.lower - d : d > c.upper ? d - c.upper : 0.0; }

void fold_accuracy(BenchRecord& r, const std::vector<Certified>& exact, const std::vector<SolidDistanceResult>& fast,
                   const std::vector<SolidDistanceResult>& proven, const std::vector<double>& fcl,
                   const std::vector<SolidDistanceResult>& coherent = {}) {
  for (std::size_t i = 0; i < exact.size(); ++i) {
    if (!exact[i].ok) {
      ++r.exact_uncertified;
      continue;
    }
    ++r.exact_frames;
    // Rounding the fast engine accounts for, relative to the query scale (SPEC section 6).
    const double slack = 1e-12;
    // A revdist answer: its error into *err, a bracket that misses the certified interval into violations.
    auto check = [&](const SolidDistanceResult& x, double* err) {
      *err = std::max(*err, error_vs(exact[i], x.distance));
      r.violations += x.lower > exact[i].upper + slack || x.upper < exact[i].lower - slack;
    };
    if (i < fast.size()) check(fast[i], &r.max_err);
    if (i < proven.size()) check(proven[i], &r.proven_max_err);
    if (i < coherent.size()) check(coherent[i], &r.max_err);
    if (i < fcl.size()) r.fcl_max_err = std::max(r.fcl_max_err, error_vs(exact[i], fcl[i]));
  }
}

struct MeshSide {
  std::shared_ptr<const FclMesh> mesh;
  long triangles = 0, bv_nodes = 0, bytes = 0;
  double build_us = 0;  // mesh + hierarchy, one build
};

MeshSide build_mesh(const Profile& p, double eps) {
  MeshSide m;
  const double c0 = thread_cpu_us();
  m.mesh = make_fcl_mesh(mesh_solid(p, eps));
  m.build_us = thread_cpu_us() - c0;
  m.triangles = fcl_mesh_triangles(*m.mesh);
  m.bv_nodes = fcl_mesh_bv_nodes(*m.mesh);
  m.bytes = fcl_mesh_bytes(*m.mesh);
  return m;
}

constexpr char kPosesMagic[] = "revdist-bench-poses/1\n";

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// Reads a poses file's fields in order; every problem is an InputError naming the file.
class PosesReader {
 public:
  PosesReader(const std::string& bytes, const std::string& file) : b_(bytes), file_(file) {}
  template <class T>
  T get(const char* what) {
    if (b_.size() - at_ < sizeof(T)) fail(std::string("truncated at ") + what);
    T v;
    std::memcpy(&v, b_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  double number(const char* what) {
    const double v = get<double>(what);
    if (!std::isfinite(v)) fail(std::string(what) + " is not finite");
    return v;
  }
  std::string text(const char* what) {
    const auto n = get<std::uint32_t>(what);
    if (n > 4096 || b_.size() - at_ < n) fail(std::string(what) + ": bad length");
    std::string t = b_.substr(at_, n);
    at_ += n;
    return t;
  }
  void expect_magic() {
    const std::size_t n = sizeof kPosesMagic - 1;
    if (b_.compare(0, n, kPosesMagic) != 0) fail("not a revdist-bench-poses/1 file");
    at_ = n;
  }
  void expect_end() {
    if (at_ != b_.size()) fail(std::to_string(b_.size() - at_) + " bytes after the last frame");
  }
  std::size_t left() const { return b_.size() - at_; }
  [[noreturn]] void fail(const std::string& problem) const { throw InputError(file_ + ": " + problem); }

 private:
  const std::string& b_;
  std::string file_;
  std::size_t at_ = 0;
};

// The size of one stored frame: 26 doubles and the evaluation count.
constexpr std::size_t kFrameBytes = 26 * sizeof(double) + sizeof(std::int32_t);

// A frame's pose arrays in stored order (rotations column-major), with their lengths.
struct PoseArray {
  double* p;
  int n;
};
std::array<PoseArray, 4> pose_arrays(MotionFrame& f) {
  return {{{f.R_WA.data(), 9}, {f.t_WA.data(), 3}, {f.R_WB.data(), 9}, {f.t_WB.data(), 3}}};
}

// The exact size of a poses file for these source and pair names, n frames each.
std::uintmax_t poses_bytes(const std::string& source, const std::vector<std::string>& names, int n) {
  std::uintmax_t size = (sizeof kPosesMagic - 1) + 8 + 4 + 4 + 4 + source.size();
  for (const std::string& name : names) size += 4 + name.size() + 4 + static_cast<std::uintmax_t>(n) * kFrameBytes;
  return size;
}

class Runner {
 public:
  Runner(const BenchInput& in, const BenchOptions& o) : in_(in), o_(o) {}

  BenchResult run() {
    const double c0 = thread_cpu_us();
    BenchResult out;
    out.options = o_;
    out.source = in_.source;
    fine_eps_ = *std::min_element(o_.eps.begin(), o_.eps.end());
    // The motion setup needs the gap to ~1e-3 of the size: finer trees only cost time.
    double extent = INFINITY;
    for (const auto& st : in_.statics) extent = std::min(extent, profile_extent(profile_at(st.def, 0.0)));
    setup_eps_ = std::max(fine_eps_, 1e-4 * extent);
    make_motions();
    for (double eps : o_.eps) run_eps(eps, out.records);
    sweep(out.records);
    out.cpu_s = (thread_cpu_us() - c0) * 1e-6;
    return out;
  }

 private:
  struct PairMotion {
    std::size_t a, b;  // static indices (motion) or static a / deformable b (deform)
    std::string name;
    std::vector<MotionFrame> frames;
    std::vector<int> sample;
    std::vector<Certified> exact;
    std::vector<char> overlapping;  // per frame: the solids overlap (or touch); motion pairs only
  };

  void say(const std::string& s) const {
    if (o_.progress) o_.progress(s);
  }

  std::unique_ptr<Built> build(const Profile& p, double eps) const {
    auto b = std::make_unique<Built>();
    b->profile = p;
    b->tree = build_biarc_tree(b->profile, eps, &b->stats);
    return b;
  }

  // Frames (setup queries on the finest trees, or the poses file) and
  // certified distances of the sample frames.
  void make_motions() {
    // The pairs in run order (Figure 12's, then the deformable ones): their
    // names and the sum of their two solids' reaches (profile_reach).
    std::vector<std::string> names;
    std::vector<double> reaches;
    auto reach = [](const SolidDef& d) {
      double r = 0;
      for (const Profile& p : d.keyframes) r = std::max(r, profile_reach(p));
      return r;
    };
    auto plan = [&](const BenchInput::Solid& a, const BenchInput::Solid& b) {
      names.push_back(a.name + "-" + b.name);
      reaches.push_back(reach(a.def) + reach(b.def));
    };
    for (std::size_t i = 0; i < in_.statics.size(); ++i)
      for (std::size_t j = i; j < in_.statics.size(); ++j) plan(in_.statics[i], in_.statics[j]);
    for (const auto& d : in_.deformables)
      for (const auto& st : in_.statics) plan(st, d);
    std::error_code ec;
    const bool from_file = !o_.poses_file.empty() && std::filesystem::exists(o_.poses_file, ec);
    if (ec) throw InputError(o_.poses_file + ": cannot read (" + ec.message() + ")");
    BenchPoses stored;
    if (from_file) stored = read_poses(names, reaches);
    else if (!o_.poses_file.empty()) check_poses_writable();
    std::size_t next = 0;  // the next stored pair
    // The next pair's frames: stored, or placed by `place` and snapped.
    auto frames_of = [&](auto&& place) {
      if (from_file) return stored.pairs[next++].second;
      std::vector<MotionFrame> f = place();
      snap_to_quaternions(f);
      return f;
    };
    std::vector<std::unique_ptr<Built>> fine;
    if (!from_file)
      for (const auto& s : in_.statics) fine.push_back(build(profile_at(s.def, 0.0), setup_eps_));
    MotionOptions mo;
    mo.frames = o_.frames;
    std::uint64_t seed = o_.seed;
    for (std::size_t i = 0; i < in_.statics.size(); ++i) {
      for (std::size_t j = i; j < in_.statics.size(); ++j) {
        PairMotion pm{i, j, in_.statics[i].name + "-" + in_.statics[j].name, {}, {}, {}, {}};
        say("motion frames: " + pm.name);
        mo.seed = seed++;
        pm.frames = frames_of([&] {
          const Built* fb = fine[j].get();
          return near_contact_motion(fine[i]->posed(), [fb](int) { return fb->posed(); }, mo);
        });
        certify(pm, [this, i](int) { return profile_at(in_.statics[i].def, 0.0); },
                [this, j](int) { return profile_at(in_.statics[j].def, 0.0); });
        classify(pm);
        motions_.push_back(std::move(pm));
      }
    }
    for (std::size_t d = 0; d < in_.deformables.size(); ++d) {
      const SolidDef& def = in_.deformables[d].def;
      std::unique_ptr<Morph> m;
      if (!from_file) m = std::make_unique<Morph>(build_morph(def, setup_eps_, o_.frames));
      const Morph* mp = m.get();
      for (std::size_t i = 0; i < in_.statics.size(); ++i) {
        PairMotion pm{i, d, in_.statics[i].name + "-" + in_.deformables[d].name, {}, {}, {}, {}};
        say("motion frames: " + pm.name);
        mo.seed = seed++;
        pm.frames = frames_of([&] {
          return near_contact_motion(fine[i]->posed(), [mp](int f) { return mp->frames[f]->posed(); }, mo);
        });
        certify(pm, [this, i](int) { return profile_at(in_.statics[i].def, 0.0); },
                [this, &def](int f) { return profile_at(def, morph_time(def, f, o_.frames)); });
        deforms_.push_back(std::move(pm));
      }
    }
    if (!from_file && !o_.poses_file.empty()) write_poses();
  }

  // The poses file, checked against this run before any frame is used.
  BenchPoses read_poses(const std::vector<std::string>& names, const std::vector<double>& reaches) const {
    const std::string& file = o_.poses_file;
    auto mismatch = [&](const std::string& what) {
      throw InputError(file + ": poses of another run (" + what + "); remove it or pass another --poses");
    };
    // Its size is known from this run: any other is refused unread.
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(file, ec);
    if (ec) throw InputError(file + ": cannot read (" + ec.message() + ")");
    if (size != poses_bytes(in_.source, names, o_.frames))
      mismatch(std::to_string(size) + " bytes, not those of " + std::to_string(names.size()) + " pairs of " +
               std::to_string(o_.frames) + " frames");
    std::string bytes(static_cast<std::size_t>(size), '\0');
    std::ifstream in(file, std::ios::binary);
    if (!in.read(bytes.data(), static_cast<std::streamsize>(size))) throw InputError(file + ": cannot read");
    BenchPoses p = decode_bench_poses(bytes, file);
    if (p.source != in_.source) mismatch("source " + quote(p.source));
    if (p.seed != o_.seed) mismatch("seed " + std::to_string(p.seed));
    if (p.frames != o_.frames) mismatch(std::to_string(p.frames) + " frames");
    if (p.pairs.size() != names.size()) mismatch(std::to_string(p.pairs.size()) + " pairs");
    for (std::size_t k = 0; k < names.size(); ++k) {
      if (p.pairs[k].first != names[k]) mismatch("pair " + quote(p.pairs[k].first) + " where this run has " + quote(names[k]));
      // The motion keeps A at its place and B within twice their reaches of it:
      // a pose far beyond (which would cost the certified engine minutes) is not one of its frames.
      const double far = 4 * reaches[k];
      for (const MotionFrame& f : p.pairs[k].second)
        if (!(f.t_WA.norm() <= far && (f.t_WB - f.t_WA).norm() <= far))
          throw InputError(file + ": pair " + quote(names[k]) + ": a pose far beyond the motion's reach");
    }
    say("motion frames from " + file);
    return p;
  }

  // Writes this run's frames to the poses file (a temporary file renamed over it).
  void write_poses() const {
    BenchPoses p;
    p.source = in_.source, p.seed = o_.seed, p.frames = o_.frames;
    for (const auto* set : {&motions_, &deforms_})
      for (const PairMotion& pm : *set) p.pairs.emplace_back(pm.name, pm.frames);
    const std::string bytes = encode_bench_poses(p);
    const std::string tmp = poses_tmp();
    std::error_code ec;
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      out.close();
      if (!out) {
        std::filesystem::remove(tmp, ec);
        throw InputError(o_.poses_file + ": cannot write");
      }
    }
    std::filesystem::rename(tmp, o_.poses_file, ec);
    if (ec) {
      const std::string why = ec.message();
      std::filesystem::remove(tmp, ec);
      throw InputError(o_.poses_file + ": cannot write (" + why + ")");
    }
    say("motion frames written to " + o_.poses_file);
  }

  std::string poses_tmp() const { return o_.poses_file + ".tmp" + std::to_string(static_cast<long>(getpid())); }

  // Before any frame is placed: a poses file that cannot be written is refused now, not after the motions.
  void check_poses_writable() const {
    const std::string tmp = poses_tmp();
    errno = 0;
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    const bool ok = static_cast<bool>(out);
    const int err = errno;
    out.close();
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    if (!ok) throw InputError(o_.poses_file + ": cannot write" + (err ? std::string(" (") + std::strerror(err) + ")" : ""));
  }

  void certify(PairMotion& pm, const std::function<Profile(int)>& pa, const std::function<Profile(int)>& pb) {
    pm.sample = sample_frames(static_cast<int>(pm.frames.size()), o_.exact_frames);
    ExactSolidOptions xo;
    xo.absolute_width = 0.1 * fine_eps_;  // fine enough to see each side's error at the finest eps
    xo.max_boxes = o_.exact_max_boxes;
    for (int j : pm.sample) {
      say("certified reference: " + pm.name + " frame " + std::to_string(j));
      const MotionFrame& f = pm.frames[j];
      Pose A, B;  // the exact engine takes quaternions; the frame's rotations are orthonormal doubles
      const Eigen::Quaterniond qa(f.R_WA), qb(f.R_WB);
      A.q = {qa.w(), qa.x(), qa.y(), qa.z()}, A.translation = f.t_WA;
      B.q = {qb.w(), qb.x(), qb.y(), qb.z()}, B.translation = f.t_WB;
      const ExactSolidResult r = solid_distance_exact(pa(j), A, pb(j), B, xo);
      pm.exact.push_back({r.certified && r.width_reached, r.lower, r.upper});
      if (!(r.certified && r.width_reached)) {
        std::ostringstream m;
        m << "certified reference: " << pm.name << " frame " << j << " not counted: " << (r.certified ? "proven [" : "unproven [")
          << r.lower << ", " << r.upper << "] after " << r.boxes << " boxes, " << r.time_ms / 1000 << " s CPU"
          << (r.reason.empty() ? std::string() : " (" + r.reason + ")");
        say(m.str());
      }
    }
  }

  // Which frames overlap: the fast engine at tol 1e-9 x size on the finest
  // trees proves an overlap, or brackets the distance in [0, tol] (touching:
  // counted as overlapping, the harder side of the target). A frame planned
  // to overlap may not: see BenchRecord::planned_overlaps.
  void classify(PairMotion& pm) {
    say("overlap reference: " + pm.name);
    const Built& a = reference(pm.a);
    const Built& b = reference(pm.b);
    DistanceOptions o;
    o.tol = 1e-9 * std::max(profile_extent(a.profile), profile_extent(b.profile));
    for (const MotionFrame& f : pm.frames) {
      PosedSolid A = a.posed(), B = b.posed();
      A.R = f.R_WA, A.t = f.t_WA, B.R = f.R_WB, B.t = f.t_WB;
      const SolidDistanceResult r = solid_distance(A, B, o);
      pm.overlapping.push_back(r.overlap || r.lower <= 0);
    }
  }
  // Static solid i's tree at the finest eps (the overlap reference's), built once.
  const Built& reference(std::size_t i) {
    while (reference_.size() <= i)
      reference_.push_back(build(profile_at(in_.statics[reference_.size()].def, 0.0), fine_eps_));
    return *reference_[i];
  }

  // The certified sample used the quaternion's rotation: time every side at that same pose.
  static void snap_to_quaternions(std::vector<MotionFrame>& frames) {
    for (MotionFrame& f : frames) {
      const Eigen::Quaterniond qa(f.R_WA), qb(f.R_WB);
      Pose A, B;
      A.q = {qa.w(), qa.x(), qa.y(), qa.z()}, B.q = {qb.w(), qb.x(), qb.y(), qb.z()};
      f.R_WA = A.rotation(), f.R_WB = B.rotation();
    }
  }

  void run_eps(double eps, std::vector<BenchRecord>& records) {
    const std::string el = eps_label(eps);
    // Tables 1-2 and Figure 9: trees, meshes, build times.
    std::vector<std::unique_ptr<Built>> trees;
    std::vector<MeshSide> meshes;
    for (const auto& s : in_.statics) {
      say("build " + s.name + " eps " + el);
      trees.push_back(build(profile_at(s.def, 0.0), eps));
      const Built& t = *trees.back();
      const std::vector<double> us = time_rebuilds(t.profile, eps, 41);
      BenchRecord r;
      r.experiment = "build", r.pair = s.name, r.eps = eps, r.tol = 2 * eps;
      r.samples = static_cast<int>(us.size());
      r.median_us = nearest_rank_percentile(us, 0.5), r.p90_us = nearest_rank_percentile(us, 0.9), r.mean_us = mean(us);
      r.nodes = t.stats.nodes, r.leaves = t.stats.leaves, r.bytes = static_cast<long>(t.stats.bytes);
      r.fcl_median_us = r.fcl_p90_us = r.fcl_mean_us = r.ratio = NAN;
      if (o_.fcl) {
        say("mesh " + s.name + " eps " + el);
        meshes.push_back(build_mesh(t.profile, eps));
        const MeshSide& m = meshes.back();
        r.fcl_median_us = r.fcl_p90_us = r.fcl_mean_us = m.build_us;
        r.ratio = m.build_us / r.median_us;
        r.fcl_triangles = m.triangles, r.fcl_bv_nodes = m.bv_nodes, r.fcl_bytes = m.bytes;
      }
      records.push_back(r);
    }
    // Figure 9's last bar and Figure 8: the deformable model rebuilt every frame.
    for (std::size_t d = 0; d < in_.deformables.size(); ++d) {
      const auto& def = in_.deformables[d];
      say("rebuild " + def.name + " over " + std::to_string(o_.frames) + " frames, eps " + el);
      const Morph m = build_morph(def.def, eps, o_.frames);
      BenchRecord r;
      r.experiment = "build", r.pair = def.name, r.eps = eps, r.tol = 2 * eps;
      r.samples = static_cast<int>(m.rebuild_us.size());
      r.median_us = nearest_rank_percentile(m.rebuild_us, 0.5), r.p90_us = nearest_rank_percentile(m.rebuild_us, 0.9);
      r.mean_us = mean(m.rebuild_us);
      for (const auto& f : m.frames) {
        r.nodes = std::max<long>(r.nodes, f->stats.nodes), r.leaves = std::max<long>(r.leaves, f->stats.leaves);
        r.bytes = std::max<long>(r.bytes, static_cast<long>(f->stats.bytes));
      }
      r.fcl_median_us = r.fcl_p90_us = r.fcl_mean_us = r.ratio = NAN;
      if (o_.fcl) {
        // One mesh rebuild of the first frame: what FCL would pay per frame.
        const MeshSide ms = build_mesh(m.frames[0]->profile, eps);
        r.fcl_median_us = r.fcl_p90_us = r.fcl_mean_us = ms.build_us;
        r.ratio = ms.build_us / r.mean_us;
        r.fcl_triangles = ms.triangles, r.fcl_bv_nodes = ms.bv_nodes, r.fcl_bytes = ms.bytes;
      }
      records.push_back(r);
      for (PairMotion& pm : deforms_) {
        if (pm.b != d) continue;
        say("deform " + pm.name + " eps " + el);
        const Built* ta = trees[pm.a].get();
        const QueryTimes q = time_queries(
            pm.frames, [ta](int) { return ta->posed(); }, [&m](int f) { return m.frames[f]->posed(); }, 2 * eps,
            pm.sample, {});
        BenchRecord dr;
        dr.experiment = "deform", dr.pair = pm.name, dr.eps = eps, dr.tol = 2 * eps;
        set_counters(dr, q);
        dr.nodes = ta->stats.nodes + r.nodes, dr.leaves = ta->stats.leaves + r.leaves, dr.bytes = ta->tree.bytes() + r.bytes;
        dr.fcl_median_us = dr.fcl_p90_us = dr.fcl_mean_us = dr.ratio = NAN;
        dr.proven_median_us = dr.proven_p90_us = NAN;
        fold_accuracy(dr, pm.exact, q.sample, {}, {});
        records.push_back(dr);
      }
    }
    // Figure 12: every pair in near-contact motion, revdist (tol 2 eps and the proven mode) and FCL.
    QueryTimes all, all_proven, all_coherent;
    std::vector<double> all_fcl, all_zero_us;
    BenchRecord total;
    for (PairMotion& pm : motions_) {
      say("motion " + pm.name + " eps " + el + " (" + std::to_string(pm.frames.size()) + " frames)");
      const Built* ta = trees[pm.a].get();
      const Built* tb = trees[pm.b].get();
      auto fa = [ta](int) { return ta->posed(); };
      auto fb = [tb](int) { return tb->posed(); };
      const QueryTimes q = time_queries(pm.frames, fa, fb, 2 * eps, pm.sample, pm.overlapping);
      const QueryTimes qp = time_queries(pm.frames, fa, fb, o_.proven_tol, pm.sample, pm.overlapping);
      const QueryTimes qc = time_queries(pm.frames, fa, fb, 2 * eps, pm.sample, pm.overlapping, true);
      BenchRecord r;
      r.experiment = "motion", r.pair = pm.name, r.eps = eps, r.tol = 2 * eps;
      set_counters(r, q);
      r.proven_median_us = nearest_rank_percentile(qp.us, 0.5), r.proven_p90_us = nearest_rank_percentile(qp.us, 0.9);
      set_coherent(r, qc);
      r.nodes = ta->stats.nodes + tb->stats.nodes, r.leaves = ta->stats.leaves + tb->stats.leaves;
      r.bytes = static_cast<long>(ta->tree.bytes() + tb->tree.bytes());
      r.fcl_median_us = r.fcl_p90_us = r.fcl_mean_us = r.ratio = NAN;
      std::vector<double> fcl_sample;
      if (o_.fcl) {
        const MeshSide& ma = meshes[pm.a];
        const MeshSide& mb = meshes[pm.b];
        std::vector<double> us, zero_us;
        std::size_t next = 0;
        for (int j = 0; j < static_cast<int>(pm.frames.size()); ++j) {
          const MotionFrame& f = pm.frames[j];
          const FclDistanceResult fr = fcl_mesh_distance(*ma.mesh, f.R_WA, f.t_WA, *mb.mesh, f.R_WB, f.t_WB);
          us.push_back(fr.cpu_us);
          r.fcl_zero += fr.distance == 0;
          if (fr.distance == 0) zero_us.push_back(q.us[j]);
          if (next < pm.sample.size() && pm.sample[next] == j) fcl_sample.push_back(fr.distance), ++next;
        }
        r.fcl_zero_p99_us = nearest_rank_percentile(zero_us, 0.99);
        all_zero_us.insert(all_zero_us.end(), zero_us.begin(), zero_us.end());
        r.fcl_median_us = nearest_rank_percentile(us, 0.5);
        r.fcl_p90_us = nearest_rank_percentile(us, 0.9);
        r.fcl_mean_us = mean(us);
        all_fcl.insert(all_fcl.end(), us.begin(), us.end());
        r.ratio = r.fcl_median_us / r.median_us;
        r.fcl_triangles = ma.triangles + mb.triangles, r.fcl_bv_nodes = ma.bv_nodes + mb.bv_nodes;
        r.fcl_bytes = ma.bytes + mb.bytes;
      }
      fold_accuracy(r, pm.exact, q.sample, qp.sample, fcl_sample, qc.sample);
      records.push_back(r);
      merge(all, q), merge(all_proven, qp), merge(all_coherent, qc);
      total.nodes += r.nodes, total.leaves += r.leaves, total.bytes += r.bytes, total.fcl_zero += r.fcl_zero;
      total.exact_frames += r.exact_frames, total.exact_uncertified += r.exact_uncertified;
      total.violations += r.violations, total.max_err = std::max(total.max_err, r.max_err);
      total.proven_max_err = std::max(total.proven_max_err, r.proven_max_err);
      total.fcl_max_err = std::max(total.fcl_max_err, r.fcl_max_err);
      total.fcl_triangles += r.fcl_triangles, total.fcl_bv_nodes += r.fcl_bv_nodes, total.fcl_bytes += r.fcl_bytes;
    }
    if (motions_.empty()) return;
    // Every frame of every pair: the distribution the targets speak of. Sizes are sums over the pairs.
    BenchRecord& t = total;
    t.experiment = "motion", t.pair = "all", t.eps = eps, t.tol = 2 * eps;
    set_counters(t, all);
    t.proven_median_us = nearest_rank_percentile(all_proven.us, 0.5);
    t.proven_p90_us = nearest_rank_percentile(all_proven.us, 0.9);
    set_coherent(t, all_coherent);
    t.fcl_median_us = nearest_rank_percentile(all_fcl, 0.5);
    t.fcl_zero_p99_us = nearest_rank_percentile(all_zero_us, 0.99);
    t.fcl_p90_us = nearest_rank_percentile(all_fcl, 0.9);
    t.fcl_mean_us = mean(all_fcl);
    t.ratio = t.fcl_median_us / t.median_us;
    records.push_back(t);
  }

  // revdist alone on every Figure 12 frame at each sweep eps (tol 2 eps), one
  // record "all" per eps: how query time grows as eps shrinks.
  void sweep(std::vector<BenchRecord>& records) {
    if (motions_.empty()) return;
    std::vector<double> eps = o_.sweep_eps;
    if (eps.empty()) {
      const double hi = *std::max_element(o_.eps.begin(), o_.eps.end());
      double floor = 0;  // no fit finer than 1e-9 of the largest static solid
      for (const auto& s : in_.statics) floor = std::max(floor, 1e-9 * solid_extent(s.def));
      for (double e = hi; e >= 0.01 * fine_eps_ * (1 - 1e-9) && e >= floor; e /= 10) eps.push_back(e);
    }
    std::sort(eps.rbegin(), eps.rend());
    eps.erase(std::unique(eps.begin(), eps.end()), eps.end());
    if (eps.size() < 2) return;
    for (double e : eps) {
      const std::string el = eps_label(e);
      say("sweep eps " + el);
      std::vector<std::unique_ptr<Built>> trees;
      for (const auto& s : in_.statics) trees.push_back(build(profile_at(s.def, 0.0), e));
      QueryTimes all;
      BenchRecord r;
      r.experiment = "sweep", r.pair = "all", r.eps = e, r.tol = 2 * e;
      for (const PairMotion& pm : motions_) {
        const Built* ta = trees[pm.a].get();
        const Built* tb = trees[pm.b].get();
        merge(all, time_queries(pm.frames, [ta](int) { return ta->posed(); }, [tb](int) { return tb->posed(); }, 2 * e,
                                {}, pm.overlapping));
        r.nodes += ta->stats.nodes + tb->stats.nodes, r.leaves += ta->stats.leaves + tb->stats.leaves;
        r.bytes += static_cast<long>(ta->tree.bytes() + tb->tree.bytes());
      }
      set_counters(r, all);
      r.fcl_median_us = r.fcl_p90_us = r.fcl_mean_us = r.ratio = NAN;
      r.proven_median_us = r.proven_p90_us = NAN;
      records.push_back(r);
    }
  }

  static void merge(QueryTimes& into, const QueryTimes& q) {
    into.us.insert(into.us.end(), q.us.begin(), q.us.end());
    into.planned_overlaps += q.planned_overlaps;
    into.overlap_us.insert(into.overlap_us.end(), q.overlap_us.begin(), q.overlap_us.end());
    into.proven_overlap_us.insert(into.proven_overlap_us.end(), q.proven_overlap_us.begin(), q.proven_overlap_us.end());
    into.node_pairs += q.node_pairs, into.leaf_pairs += q.leaf_pairs, into.patch_pairs += q.patch_pairs;
    into.quick_pairs += q.quick_pairs, into.local_pairs += q.local_pairs, into.refined += q.refined;
    into.overlaps += q.overlaps, into.unconverged += q.unconverged;
  }

  const BenchInput& in_;
  const BenchOptions& o_;
  double fine_eps_ = 1e-5, setup_eps_ = 1e-5;
  std::vector<PairMotion> motions_, deforms_;
  std::vector<std::unique_ptr<Built>> reference_;  // static trees at fine_eps_ (classify)
};

BenchInput::Solid solid_named(const Case& c, const std::string& name, const std::string& file) {
  for (const SolidDef& s : c.solids)
    if (s.name == name) return {name, s};
  throw InputError(file + ": solid \"" + name + "\" not found (the paper benchmark needs it)");
}

}  // namespace

std::string default_models_dir() {
  if (const char* d = std::getenv("REVDIST_MODELS_DIR")) return d;
  return std::string(REVDIST_SOURCE_DIR) + "/cases/models";
}

BenchInput paper_bench_input(const std::string& models_dir) {
  BenchInput in;
  in.source = "paper";
  const std::string pairs = models_dir + "/paper_pairs.json", morph = models_dir + "/morph.json";
  const Case c = read_case(pairs);
  for (const char* name : {"pawn", "cup", "bottle", "table", "lightmil"}) in.statics.push_back(solid_named(c, name, pairs));
  in.deformables.push_back(solid_named(read_case(morph), "morph", morph));
  in.deformables.back().name = "Mt";
  return in;
}

BenchInput case_bench_input(const std::string& case_file) {
  BenchInput in;
  in.source = case_file;
  const Case c = read_case(case_file);
  for (const SolidDef& s : c.solids) (s.deformable() ? in.deformables : in.statics).push_back({s.name, s});
  if (in.statics.empty()) throw InputError(case_file + ": no static solid to benchmark (keyframed solids play Mt against static ones)");
  return in;
}

std::string encode_bench_poses(const BenchPoses& poses) {
  std::string out(kPosesMagic);
  put(out, poses.seed);
  put(out, static_cast<std::int32_t>(poses.frames));
  put(out, static_cast<std::int32_t>(poses.pairs.size()));
  auto text = [&](const std::string& t) {
    put(out, static_cast<std::uint32_t>(t.size()));
    out += t;
  };
  text(poses.source);
  for (const auto& [name, frames] : poses.pairs) {
    text(name);
    put(out, static_cast<std::int32_t>(frames.size()));
    for (MotionFrame f : frames) {
      for (const PoseArray& a : pose_arrays(f)) out.append(reinterpret_cast<const char*>(a.p), a.n * sizeof(double));
      put(out, f.target);
      put(out, f.achieved);
      put(out, static_cast<std::int32_t>(f.evaluations));
    }
  }
  return out;
}

BenchPoses decode_bench_poses(const std::string& bytes, const std::string& file) {
  PosesReader r(bytes, file);
  r.expect_magic();
  BenchPoses p;
  p.seed = r.get<std::uint64_t>("seed");
  p.frames = r.get<std::int32_t>("frames");
  const std::int32_t pairs = r.get<std::int32_t>("pairs");
  if (p.frames < 1 || pairs < 0 || pairs > 100000) r.fail("frames or pairs out of range");
  p.source = r.text("source");
  for (std::int32_t k = 0; k < pairs; ++k) {
    std::string name = r.text("pair name");
    const std::int32_t n = r.get<std::int32_t>("frame count");
    if (n != p.frames) r.fail("pair " + quote(name) + " holds " + std::to_string(n) + " frames, the header says " +
                              std::to_string(p.frames));
    if (r.left() / kFrameBytes < static_cast<std::size_t>(n)) r.fail("truncated in pair " + quote(name));
    std::vector<MotionFrame> frames(n);
    for (MotionFrame& f : frames) {
      for (const PoseArray& a : pose_arrays(f))
        for (int i = 0; i < a.n; ++i) a.p[i] = r.number("a pose coordinate");
      f.target = r.number("a target gap");
      f.achieved = r.number("an achieved gap");
      f.evaluations = r.get<std::int32_t>("an evaluation count");
      if (f.achieved < 0 || f.evaluations < 0) r.fail("pair " + quote(name) + ": a negative gap or evaluation count");
      for (const Mat3* R : {&f.R_WA, &f.R_WB})
        if (!((R->transpose() * *R - Mat3::Identity()).cwiseAbs().maxCoeff() <= 1e-9) || !(R->determinant() > 0))
          r.fail("pair " + quote(name) + ": a rotation is not orthonormal");
    }
    p.pairs.emplace_back(std::move(name), std::move(frames));
  }
  r.expect_end();
  return p;
}

void check_bench(const BenchInput& input, const BenchOptions& options) {
  if (options.eps.empty()) throw InputError("--eps: at least one value");
  for (double e : options.eps)
    if (!(e > 0) || !std::isfinite(e)) throw InputError("--eps: every value must be a finite positive number");
  for (double e : options.sweep_eps)
    if (!(e > 0) || !std::isfinite(e)) throw InputError("sweep eps: every value must be a finite positive number");
  if (options.frames < 1) throw InputError("--frames must be at least 1");
  // (2000 frames take about 3 minutes; 10^6 was accepted and ran for hours.)
  if (options.frames > kMaxBenchFrames)
    throw InputError("--frames " + std::to_string(options.frames) + ": at most " + std::to_string(kMaxBenchFrames) +
                     " (2000 take about 3 minutes)");
  // A poses file that is there must be a file whose size can be read (it is
  // read once the run has begun: /dev/null was refused after the banner).
  if (!options.poses_file.empty()) {
    std::error_code ec;
    const auto st = std::filesystem::status(options.poses_file, ec);
    if (std::filesystem::exists(st) && !std::filesystem::is_regular_file(st))
      throw InputError(options.poses_file + ": cannot read (not a regular file)");
  }
  // Before any work: fits below what doubles resolve, and meshes beyond the
  // memory limit, are refused (a 1e-8 mesh of a ball took 6 GB, 1e-20 crashed).
  std::vector<const BenchInput::Solid*> all;
  for (const auto& s : input.statics) all.push_back(&s);
  for (const auto& s : input.deformables) all.push_back(&s);
  const std::string hint = "use a larger --eps or --no-fcl";
  for (const BenchInput::Solid* s : all) {
    const std::string who = input.source + ": solid " + quote(s->name);
    for (double e : options.sweep_eps) require_resolvable_eps(e, solid_extent(s->def), who);
    for (double e : options.eps) {
      require_resolvable_eps(e, solid_extent(s->def), who);
      if (options.fcl)
        for (const Profile& p : s->def.keyframes) require_meshes_within_limit({&p}, e, who, hint);
    }
  }
  // At one eps the static solids' meshes are alive together, with one frame
  // of a deformable solid's beside them.
  if (!options.fcl) return;
  std::vector<Profile> statics;
  for (const auto& s : input.statics) statics.push_back(profile_at(s.def, 0.0));
  std::vector<const Profile*> alive;
  for (const Profile& p : statics) alive.push_back(&p);
  for (double e : options.eps) {
    require_meshes_within_limit(alive, e, input.source, hint);
    for (const auto& d : input.deformables) {
      const Profile first = profile_at(d.def, 0.0);  // (its mesh is built for the first frame only)
      alive.push_back(&first);
      require_meshes_within_limit(alive, e, input.source, hint);
      alive.pop_back();
    }
  }
}

BenchResult run_bench(const BenchInput& input, const BenchOptions& options) {
  check_bench(input, options);
  return Runner(input, options).run();
}

}  // namespace revdist
