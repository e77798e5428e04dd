// Reading and validating `revdist/1` cases (SPEC section 3) and blending the
// profiles of deformable (keyframed) solids.
#pragma once
#include <string>

#include "core/profile.h"

namespace revdist {

// Reads a revdist/1 case. Every problem is an InputError with one line
//   "FILE: solid \"vase\" piece 2: weight -1 <= 0"
//   "FILE: solid \"morph\" keyframe 1 piece 0: ..."   (pieces and keyframes count from 0,
//                                                        as JSON array indices do)
//   "FILE: instance \"b\": unknown solid \"vace\""
//   "FILE: queries[3]: unknown instance \"x\""
// Checked: JSON syntax, "format": "revdist/1", piece types and their members (unknown
// members are rejected except "comment"; unknown top-level keys are ignored), point and
// weight counts, bspline degree (integer 1..32) / knots / points consistency (knots
// clamped, non-decreasing, interior multiplicity <= degree), weights > 0, finite numbers
// everywhere, joins (profile_check.h: tolerance 1e-9 of the profile's size; joins are made
// exact), the ends (axis at both ends, or closed), r >= 0 / self-intersection of every
// static profile, every keyframe and every blended profile an instance uses at its time,
// keyframe structure (same piece kinds, degrees, point counts and knots in each keyframe),
// instance names (non-empty, unique), known solids, non-zero quaternions, queries naming
// two different known instances.
// Instances: "time" is optional (default 0) and for a deformable solid must lie in [0, K-1]; a static solid accepts no time other than 0 (a time there is
// almost certainly a mistake about which solid is keyframed). Absent "queries" means all
// pairs i < j in instance order; absent "instances" is allowed (`revdist fit` needs only
// solids). Solids are stored in the order of their names (JSON objects are unordered).
// Scenes of 10^4 instances pass all_pairs_when_absent = false: their broad phase finds
// the pairs, and n^2/2 listed queries would not fit in memory. With it true, a case
// without "queries" whose instances make more than kMaxAllPairs pairs is an InputError.
inline constexpr std::size_t kMaxAllPairs = 100000;
// An instance's optional "motion" (core/motion.h) moves it over `revdist scene` frames.
Case read_case(const std::string& path, bool all_pairs_when_absent = true);
// The same on text in memory (the fuzz target's entry); path only names it in messages.
Case read_case_text(const std::string& text, const std::string& path);

// The profile of a solid at keyframe time s (clamped to [0, K-1]): control points and
// weights blended linearly between keyframes floor(s) and ceil(s) (missing weights count
// as 1); arcs and lines blend their three / two points; knots are those of keyframe 0.
// At an integer time, exactly that keyframe. Static solids: the one profile.
Profile profile_at(const SolidDef& solid, double time);

}  // namespace revdist
