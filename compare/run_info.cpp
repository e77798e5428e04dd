// Build and machine description recorded in stress and compare reports.
#include "compare/run_info.h"

#include <sys/utsname.h>

#include <fstream>
#include <string>
#include <thread>

namespace revdist {

nlohmann::json run_info() {
  utsname u{};
  uname(&u);
  std::string cpu = "unknown";
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  return {{"build_type", REVDIST_BUILD_TYPE},
          {"build_flags", REVDIST_BUILD_FLAGS},
          {"compiler", __VERSION__},
          {"machine", std::string(u.sysname) + " " + u.release + " " + u.machine},
          {"cpu", cpu},
          {"cores", std::thread::hardware_concurrency()}};
}

}  // namespace revdist
