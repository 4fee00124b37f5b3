// Runs the caustica executable and captures its exit code and output.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <filesystem>
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

// A shell prefix that limits the address space to `kib` KiB (ulimit -v), or "" where that cannot
// work: AddressSanitizer reserves terabytes of shadow address space at start-up.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSpaceLimits = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)  // clang before 22 does not define __SANITIZE_ADDRESS__
constexpr bool kAddressSpaceLimits = false;
#else
constexpr bool kAddressSpaceLimits = true;
#endif
#else
constexpr bool kAddressSpaceLimits = true;
#endif
// Built with AddressSanitizer, whose runs are several times slower: the statistical render
// comparisons then render a little and check what a sanitizer checks (the Release suite holds
// them to their figures).
constexpr bool kSanitized = !kAddressSpaceLimits;
inline std::string address_space_limit(size_t kib) { return "ulimit -v " + std::to_string(kib) + " && "; }

// A 16x16 scene with a floor and a small area light, for command-line tests.
inline const char* kLitFloorScene = R"({
  "camera": {"position": [0, 1, 3], "look_at": [0, 1, 0], "fov": 50},
  "render": {"width": 16, "height": 16, "spp": 2},
  "materials": {"white": {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]},
                "lamp": {"type": "diffuse", "albedo": [0, 0, 0], "emission": [5, 5, 5]}},
  "objects": [
    {"type": "quad", "origin": [-2, 0, -2], "edge1": [0, 0, 4], "edge2": [4, 0, 0], "material": "white"},
    {"type": "quad", "origin": [-0.5, 2, -0.5], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "material": "lamp"}
  ]
})";

// True when the folder holds nothing but the captured output, scene files and scripts: no image
// (nor its temporary file) was written.
inline bool no_images_left(const TempDir& dir) {
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    const std::string name = e.path().filename().string();
    const auto ext = e.path().extension();
    if (name != "stdout.txt" && name != "stderr.txt" && ext != ".json" && ext != ".sh") return false;
  }
  return true;
}

}  // namespace caustica::test
