// Stored references for the figure tests: a converged render made once, by
// scripts/make-test-refs.sh, and kept under tests/data/refs/ instead of being rendered again on
// every run of the suite.
//
// Each reference is three files: NAME.exr (the mean of its batches), NAME.stderr.exr (each
// pixel's standard error of that mean, from the spread of its batches, as Mitsuba 3's render
// tests keep a variance image) and NAME.json (how it was rendered: integrator, settings, spp,
// size, seed, batches, the commit and the key of its inputs). The key hashes the scene text,
// the integrator, its settings, spp, size and seed: a test whose scene or reference settings
// change fails until the script renders the reference again, and the commit that stores the new
// one says why the truth changed.
#pragma once
#include <cstdint>
#include <string>
#include "core/image.h"

namespace caustica::test {

struct ReferenceSpec {
  std::string name;  // file stem under tests/data/refs/
  std::string scene;  // scene text (JSON or Mitsuba XML)
  std::string integrator = "path";
  std::string settings = "{}";
  int spp = 0, width = 0, height = 0;
  uint64_t seed = 3;
  std::string base_dir = ".";  // where the scene's files are found
};

struct Reference {
  Image image;  // the mean
  Image standard_error;  // per pixel and channel, of the mean
};

// The stored reference for `spec`; fails the test (REQUIRE) when it is missing or stale. With the
// environment variable CAUSTICA_WRITE_REFS=1 (scripts/make-test-refs.sh) a missing or stale
// reference is rendered in kReferenceBatches batches of spp / batches samples with seeds
// seed * 1000 + batch, and written.
Reference stored_reference(const ReferenceSpec& spec);
constexpr int kReferenceBatches = 8;
// The same for `path` with `settings` (none by default).
Reference stored_path_reference(const std::string& name, const std::string& scene, int spp, int width, int height,
                                uint64_t seed = 3, const std::string& base_dir = ".",
                                const std::string& settings = "{}");

// The standard error of the mean of a rectangle of pixels (the channels' average), the pixels'
// errors taken as independent.
double region_standard_error(const Reference& ref, int x0, int y0, int x1, int y1);

}  // namespace caustica::test
