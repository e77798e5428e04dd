// Runs the `revdist` executable (REVDIST_BINARY) for the end-to-end CLI tests:
// exit status, stdout and stderr of one call. One stderr file per call, since
// ctest runs the tests of one binary in parallel processes.
#pragma once
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace revdist_test {

struct CommandRun {
  int status = -1;
  std::string out, err;
};

// `args` go through the shell (they may redirect stdout); `prefix` comes
// before the binary (an input redirection, `timeout 60 `).
inline CommandRun run(const std::string& args, const std::string& prefix = "") {
  static int calls = 0;
  const std::string err_file = testing::TempDir() + "revdist_cli_stderr_" + std::to_string(getpid()) + "_" +
                               std::to_string(++calls) + ".txt";
  CommandRun r;
  FILE* p = popen((prefix + REVDIST_BINARY + " " + args + " 2>" + err_file).c_str(), "r");
  if (!p) return r;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  std::ifstream e(err_file);
  std::stringstream ss;
  ss << e.rdbuf();
  r.err = ss.str();
  std::remove(err_file.c_str());
  return r;
}

}  // namespace revdist_test
