// revdist-circles/1 reader with the bad-input behaviour of SPEC section 3.
#include "core/circle_io.h"

#include "core/json_util.h"

namespace revdist {

namespace {
Circle3 read_circle(const Json& j, const JsonWhere& where) {
  if (!j.is_object()) where.fail("expected a circle {\"center\", \"normal\", \"radius\"}");
  reject_unknown_members(j, {"center", "normal", "radius"}, where);
  Circle3 c;
  c.center = read_vec3(require(j, "center", where), where / "center");
  c.normal = read_vec3(require(j, "normal", where), where / "normal");
  c.radius = read_number(require(j, "radius", where), where / "radius");
  // Exactly zero only: a tiny normal still defines a plane, and the engines
  // never divide by |n| before checking it.
  if (c.normal.squaredNorm() == 0.0 && c.normal == Vec3::Zero())
    (where / "normal").fail("the normal is the zero vector");
  if (c.radius < 0.0) (where / "radius").fail("negative radius");
  // Within kMaxMagnitude, as case files (centres 1e155 apart made the fast
  // engine answer "infinitely many").
  auto within = [&](const Vec3& v, const char* what) {
    if (!(v.cwiseAbs().maxCoeff() <= kMaxMagnitude)) (where / what).fail("a coordinate beyond +-1e100");
  };
  within(c.center, "center");
  within(c.normal, "normal");
  if (!(c.radius <= kMaxMagnitude)) (where / "radius").fail("radius beyond 1e100");
  return c;
}
}  // namespace

std::vector<CirclePair> read_circle_pairs(const std::string& path) {
  const Json doc = read_json_file(path);
  const JsonWhere top{path, ""};
  if (!doc.is_object()) top.fail("expected a JSON object");
  require_format(doc, "revdist-circles/1", top);
  const Json& pairs = require(doc, "pairs", top);
  const JsonWhere wp = top / "pairs";
  if (!pairs.is_array()) wp.fail("expected an array of pairs");
  std::vector<CirclePair> out;
  out.reserve(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const JsonWhere w = wp[i];
    if (!pairs[i].is_object()) w.fail("expected a pair {\"a\": circle, \"b\": circle}");
    // (expected and infinitely_many: the bundled families' answers, for tests.)
    reject_unknown_members(pairs[i], {"a", "b", "expected", "infinitely_many"}, w);
    out.push_back({read_circle(require(pairs[i], "a", w), w / "a"),
                   read_circle(require(pairs[i], "b", w), w / "b")});
  }
  return out;
}

}  // namespace revdist
