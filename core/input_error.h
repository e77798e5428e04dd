// The one error type for bad input: a one-line message naming the file, the item
// and the problem. The CLI prints it and exits with status 2 (SPEC section 3).
#pragma once
#include <stdexcept>
#include <string>

namespace revdist {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace revdist
