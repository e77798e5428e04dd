#include "core/format.h"

#include <cfenv>
#include <cstdio>

namespace revdist {

std::string fixed_digits(double v, int digits) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

namespace {
// glibc's printf rounds decimal conversions in the current rounding mode.
std::string digits_rounded(double v, int digits, int mode) {
  const int old = std::fegetround();
  std::fesetround(mode);
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  std::fesetround(old);
  return buf;
}
}  // namespace

std::string digits_down(double v, int digits) { return digits_rounded(v, digits, FE_DOWNWARD); }
std::string digits_up(double v, int digits) { return digits_rounded(v, digits, FE_UPWARD); }

}  // namespace revdist
