#include "support/reference.h"
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <nlohmann/json.hpp>
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "support/render_util.h"
#include "support/temp_dir.h"

namespace caustica::test {

namespace {

std::filesystem::path refs_dir() { return std::filesystem::path(CAUSTICA_SOURCE_DIR) / "tests" / "data" / "refs"; }

void fnv1a(uint64_t& h, const std::string& s) {
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  h ^= 0xff;  // a separator, so that ("ab", "c") and ("a", "bc") differ
  h *= 1099511628211ull;
}

// CAUSTICA_WRITE_REFS: "1" renders missing and stale references, "force" every one (once a run).
std::string write_mode() {
  const char* v = std::getenv("CAUSTICA_WRITE_REFS");
  return v != nullptr ? v : "";
}

Reference render_reference(const ReferenceSpec& spec) {
  REQUIRE(spec.spp % kReferenceBatches == 0);
  const int per_batch = spec.spp / kReferenceBatches;
  const size_t n = size_t(spec.width) * size_t(spec.height);
  std::vector<glm::dvec3> sum(n, glm::dvec3(0.0)), sum2(n, glm::dvec3(0.0));
  for (int b = 0; b < kReferenceBatches; ++b) {
    const Image img = render_text(spec.scene, spec.integrator, spec.settings, per_batch, spec.width, spec.height,
                                  spec.seed * 1000 + uint64_t(b), 0, spec.base_dir)
                          .image;
    for (size_t i = 0; i < n; ++i) {
      const glm::dvec3 v(img.pixels[i]);
      sum[i] += v;
      sum2[i] += v * v;
    }
  }
  Reference ref;
  ref.image = Image(spec.width, spec.height);
  ref.standard_error = Image(spec.width, spec.height);
  const double k = kReferenceBatches;
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3 mean = sum[i] / k;
    // The batches' sample variance over k gives the variance of their mean.
    const glm::dvec3 var = glm::max((sum2[i] - k * mean * mean) / (k - 1.0), glm::dvec3(0.0)) / k;
    ref.image.pixels[i] = Color(mean);
    ref.standard_error.pixels[i] = Color(glm::sqrt(var));
  }
  return ref;
}

// The key of a reference's inputs (FNV-1a over them, hex).
std::string reference_key(const ReferenceSpec& spec) {
  uint64_t h = 14695981039346656037ull;
  for (const std::string& s : {spec.scene, spec.integrator, spec.settings, std::to_string(spec.spp),
                               std::to_string(spec.width), std::to_string(spec.height), std::to_string(spec.seed),
                               std::to_string(kReferenceBatches)})
    fnv1a(h, s);
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace

Reference stored_reference(const ReferenceSpec& spec) {
  const std::filesystem::path dir = refs_dir();
  const std::string exr = (dir / (spec.name + ".exr")).string(), se = (dir / (spec.name + ".stderr.exr")).string(),
                    meta_path = (dir / (spec.name + ".json")).string();
  const std::string key = reference_key(spec);
  std::string stored_key;
  if (std::filesystem::exists(meta_path)) stored_key = nlohmann::json::parse(read_text(meta_path)).value("key", "");
  static std::set<std::string> rendered_this_run;
  const std::string mode = write_mode();
  const bool render = (mode == "1" && stored_key != key) || (mode == "force" && !rendered_this_run.count(spec.name));
  if (render) {
    rendered_this_run.insert(spec.name);
    const auto start = std::chrono::steady_clock::now();
    const Reference ref = render_reference(spec);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::filesystem::create_directories(dir);
    write_image(exr, ref.image);
    write_image(se, ref.standard_error);
    const char* commit = std::getenv("CAUSTICA_REFS_COMMIT");
    const nlohmann::json meta = {{"name", spec.name},
                                 {"integrator", spec.integrator},
                                 {"settings", nlohmann::json::parse(spec.settings)},
                                 {"spp", spec.spp},
                                 {"width", spec.width},
                                 {"height", spec.height},
                                 {"seed", spec.seed},
                                 {"batches", kReferenceBatches},
                                 {"batch_seeds", "seed * 1000 + batch"},
                                 {"commit", commit ? commit : "unknown"},
                                 {"seconds", std::round(seconds * 10) / 10},
                                 {"test", Catch::getResultCapture().getCurrentTestName()},
                                 {"key", key}};
    write_file_atomically(meta_path, meta.dump(2) + "\n", "reference's description");
    return ref;
  }
  const bool images = std::filesystem::exists(exr) && std::filesystem::exists(se);
  const std::string problem = stored_key.empty() ? "missing"
                              : stored_key != key ? "stale (its scene or settings changed)"
                              : !images           ? "missing its images"
                                                  : "";
  INFO("tests/data/refs/" << spec.name << ": " << problem
                          << "; render it with scripts/make-test-refs.sh and say in the commit why the truth changed");
  REQUIRE(problem.empty());
  Reference ref;
  ref.image = read_image(exr);
  ref.standard_error = read_image(se);
  REQUIRE(ref.image.width == spec.width);
  REQUIRE(ref.image.height == spec.height);
  REQUIRE(ref.standard_error.pixels.size() == ref.image.pixels.size());
  return ref;
}

Reference stored_path_reference(const std::string& name, const std::string& scene, int spp, int width, int height,
                                uint64_t seed, const std::string& base_dir, const std::string& settings) {
  ReferenceSpec spec;
  spec.name = name;
  spec.scene = scene;
  spec.settings = settings;
  spec.spp = spp;
  spec.width = width;
  spec.height = height;
  spec.seed = seed;
  spec.base_dir = base_dir;
  return stored_reference(spec);
}

double region_standard_error(const Reference& ref, int x0, int y0, int x1, int y1) {
  double var = 0.0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const glm::dvec3 e(ref.standard_error.at(x, y));
      const double mean_e = (e.x + e.y + e.z) / 3.0;
      var += mean_e * mean_e;
    }
  const double count = double(x1 - x0) * double(y1 - y0);
  return std::sqrt(var) / count;
}

}  // namespace caustica::test
