// What a published figure ran on: build type and flags, compiler, machine.
#pragma once
#include <nlohmann/json.hpp>

namespace revdist {

// {"build_type", "build_flags", "compiler", "machine", "cpu", "cores"}.
nlohmann::json run_info();

}  // namespace revdist
