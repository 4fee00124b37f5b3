// Runs the caustica executable and captures its exit code and output.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <string>
#include <sys/wait.h>
#include "support/temp_dir.h"

namespace caustica::test {

struct RunResult {
  int exit_code = -1;
  std::string out, err;
};

// `prefix` goes before the executable (e.g. "timeout -s INT 1 ").
inline RunResult run_caustica(const std::string& args, const TempDir& dir, const std::string& prefix = "") {
  const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
  const std::string cmd = std::string("cd '") + dir.path().string() + "' && " + prefix + "'" + CAUSTICA_EXE + "' " + args +
                          " >'" + out + "' 2>'" + err + "' </dev/null";
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_text(out);
  r.err = read_text(err);
  return r;
}

}  // namespace caustica::test
