// Numbers in messages and tables: %.*g with a number of significant digits,
// to nearest or rounded outward (a printed bound still holds what the double
// does).
#pragma once
#include <string>

namespace revdist {

// %.*g with the given significant digits.
std::string fixed_digits(double v, int digits);
// %.*g rounded towards -inf / +inf: a printed bracket still contains what the
// doubles do, and a printed minimum is one that is accepted.
std::string digits_down(double v, int digits);
std::string digits_up(double v, int digits);

}  // namespace revdist
