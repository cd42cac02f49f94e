#pragma once
// Runs the needle binary in a shell and captures its stdout, stderr and exit status.
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace needle::testing {

struct Result {
  int status = -1;
  std::string out;
  std::string err;
};

inline std::string Slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// `args` is appended to the binary's path as shell words.
inline Result RunNeedle(const std::string& args) {
  static int counter = 0;
  const std::string base =
      "/tmp/needle_cli_" + std::to_string(getpid()) + "_" + std::to_string(counter++);
  const std::string cmd =
      std::string(NEEDLE_BINARY) + " " + args + " >" + base + ".out 2>" + base + ".err";
  const int raw = std::system(cmd.c_str());
  Result r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = Slurp(base + ".out");
  r.err = Slurp(base + ".err");
  std::remove((base + ".out").c_str());
  std::remove((base + ".err").c_str());
  return r;
}

// A scratch file of this test process.
inline std::string TempPath(const std::string& name) {
  return "/tmp/needle_cli_" + std::to_string(getpid()) + "_" + name;
}

inline std::string Case(const std::string& name) {
  return std::string(NEEDLE_SOURCE_DIR) + "/cases/" + name;
}

}  // namespace needle::testing
