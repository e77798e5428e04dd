// libFuzzer target for the revdist/1 case reader (issue 10 item 15): any byte string must
// give a Case or an InputError with a one-line message; anything else (a crash, a
// sanitizer report, another exception, a hang) is a finding. Built only with clang and
// -DREVDIST_FUZZ=ON (tests/core/CMakeLists.txt); run as
//   build-fuzz/tests/core/case_reader_fuzzer -max_total_time=600 -timeout=10 CORPUS_DIR cases/distance
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/case_io.h"
#include "core/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const revdist::Case c = revdist::read_case_text(text, "fuzz.json");
    // Blending is part of reading a keyframed solid: every instance's profile.
    for (const revdist::Instance& inst : c.instances) (void)revdist::profile_at(c.solids[inst.solid], inst.time);
  } catch (const revdist::InputError& e) {
    const std::string m = e.what();
    if (m.rfind("fuzz.json: ", 0) != 0) std::abort();  // every message names the file
    if (m.find('\n') != std::string::npos) std::abort();  // and is one line
  }
  return 0;
}
