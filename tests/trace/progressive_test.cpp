// Progressive photon mapping (photon with "progressive") and SPPM: the per-pixel statistics,
// convergence towards the path tracer, determinism, and the render loop's pass control.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <thread>
#include <tbb/global_control.h>
#include "io/scene_loader.h"
#include "support/reference.h"
#include "support/render_util.h"
#include "support/scenes.h"
#include "trace/render.h"
#include "trace/sppm.h"

using namespace caustica;

namespace {

struct Job {
  std::string scene_text;
  std::string integrator;
  std::string settings = "{}";
  int width = 32, height = 32;
  int spp = 4;
  uint64_t seed = 1;
  int max_depth = 0;  // 0: the scene's
  int threads = 0;    // 0: all cores
  double time_limit = 0;
  const std::atomic<bool>* cancel = nullptr;
  std::function<void(int, double, const Image&)> on_pass;
};

struct Result {
  Image image;
  RenderStats stats;
  std::string describe;
};

Result run(const Job& job) {
  const std::string dir = std::string(CAUSTICA_SOURCE_DIR) + "/scenes";
  LoadedScene loaded = parse_scene(job.scene_text, "test.json", dir);
  Scene& scene = *loaded.scene;
  scene.render.width = job.width;
  scene.render.height = job.height;
  scene.camera.set_resolution(job.width, job.height);
  if (job.max_depth > 0) scene.render.max_depth = job.max_depth;
  JsonSource settings;
  settings.file = "test.json";
  settings.pointer = "/integrator";
  settings.value = nlohmann::json::parse(test::figure_settings(job.settings));
  std::optional<tbb::global_control> control;
  if (job.threads > 0) control.emplace(tbb::global_control::max_allowed_parallelism, size_t(job.threads));
  auto integrator = create_integrator(job.integrator, settings, scene.render);
  integrator->preprocess(scene, {job.seed, true, job.cancel});
  RenderOptions options;
  options.job.passes = test::figure_spp(job.spp);
  options.job.seed = job.seed;
  options.quiet = true;
  options.job.time_budget = job.time_limit;
  options.cancel = job.cancel;
  options.on_pass = job.on_pass;
  Result r;
  r.image = render_image(scene, *integrator, options, r.stats);
  r.describe = integrator->describe();
  return r;
}

glm::dvec3 image_mean(const Image& img) { return test::region_mean(img, 0, 0, img.width, img.height); }

// The stored path reference (tests/support/reference.h) of a scene with its emitters hidden.
test::Reference hidden_emitter_reference(const std::string& name, const std::string& scene_text, int spp, int size,
                                         uint64_t seed = 3) {
  return test::stored_path_reference(name, scene_text, spp, size, size, seed,
                                     std::string(CAUSTICA_SOURCE_DIR) + "/scenes", R"({"hide_emitters": true})");
}

// The running means after each of the pass counts in `keep` (the render runs max(keep) passes).
std::map<int, Image> snapshots(Job job, const std::vector<int>& keep) {
  std::map<int, Image> out;
  job.spp = *std::max_element(keep.begin(), keep.end());
  job.on_pass = [&](int passes, double, const Image& mean) {
    if (std::find(keep.begin(), keep.end(), passes) != keep.end()) out[passes] = mean;
  };
  const Result r = run(job);
  REQUIRE(r.stats.passes == job.spp);
  REQUIRE(out.size() == keep.size());
  // The last snapshot is the image the render returns.
  REQUIRE(image_mean(out[job.spp]).x == Approx(image_mean(r.image).x).epsilon(1e-6));
  return out;
}

// The image mean of `job` rendered by another integrator, settings, pass count and seed.
glm::dvec3 mean_with(Job job, const char* integrator, const char* settings, int spp, uint64_t seed) {
  job.integrator = integrator;
  job.settings = settings;
  job.spp = spp;
  job.seed = seed;
  return image_mean(run(job).image);
}

// Relative MSE of the means of block x block pixel squares: the per-pixel noise, which any
// method loses by averaging passes, mostly cancels; bias and blotches of the photon maps stay.
double block_relmse(const Image& img, const Image& ref, int block) {
  double sum = 0;
  int n = 0;
  for (int by = 0; by + block <= img.height; by += block) {
    for (int bx = 0; bx + block <= img.width; bx += block) {
      const glm::dvec3 a = test::region_mean(img, bx, by, bx + block, by + block);
      const glm::dvec3 b = test::region_mean(ref, bx, by, bx + block, by + block);
      for (int c = 0; c < 3; ++c) {
        sum += (a[c] - b[c]) * (a[c] - b[c]) / (b[c] * b[c] + 0.01);
        ++n;
      }
    }
  }
  return sum / n;
}

// Every pixel finite and non-negative.
bool finite_non_negative(const Image& img) {
  for (const Color& c : img.pixels) {
    if (!is_finite(c) || c.r < 0 || c.g < 0 || c.b < 0) return false;
  }
  return true;
}

const char* kProgressivePhoton = R"({"progressive": true, "photons": 2000, "caustic_photons": 2000})";
const char* kSmallSppm = R"({"photons": 2000})";

// Both progressive integrators with their small test settings, on the Cornell box.
const std::pair<std::string, std::string> kProgressiveIntegrators[] = {{"photon", kProgressivePhoton},
                                                                      {"sppm", kSmallSppm}};
Job cornell_box_job(const std::string& integrator, const std::string& settings) {
  Job job;
  job.scene_text = test::read_scene_file("scenes/cornell-box.json");
  job.integrator = integrator;
  job.settings = settings;
  return job;
}

}  // namespace

// ---- SppmPixel::add_pass -------------------------------------------------------------------

TEST_CASE("sppm pixel: add_pass follows N' = N + alpha M, r' = r sqrt(N' / (N + M)), tau' = (tau + phi) N' / (N + M)",
          "[trace][sppm][progressive]" TIER_UNIT) {
  const float alpha_f = 2.0f / 3.0f;
  const double alpha = alpha_f;  // the value add_pass receives
  SppmPixel px;
  px.radius = 2.0f;
  // By hand: pass 1, M = 12, phi = (3, 6, 9).
  double n = 0, r = 2.0;
  glm::dvec3 tau(0.0);
  auto by_hand = [&](double m, const glm::dvec3& phi) {
    const double n_new = n + alpha * m;
    const double f = n_new / (n + m);
    r *= std::sqrt(f);
    tau = (tau + phi) * f;
    n = n_new;
  };
  auto check = [&](const char* what) {
    INFO(what << ": radius " << px.radius << " (" << r << "), n " << px.n << " (" << n << "), tau " << px.tau.x << " ("
              << tau.x << ")");
    CHECK(px.n == Approx(n).epsilon(1e-9));
    CHECK(double(px.radius) == Approx(r).epsilon(1e-6));
    for (int c = 0; c < 3; ++c) CHECK(px.tau[c] == Approx(tau[c]).epsilon(1e-6));
  };
  px.add_pass(12, Color(3, 6, 9), alpha_f);
  by_hand(12, glm::dvec3(3, 6, 9));
  check("pass 1");
  // Pass 1 in numbers: N = 8, r = 2 sqrt(8 / 12), tau = (2, 4, 6).
  CHECK(px.n == Approx(8.0).epsilon(1e-6));
  CHECK(px.radius == Approx(2.0 * std::sqrt(8.0 / 12.0)).epsilon(1e-6));
  CHECK(px.tau.x == Approx(2.0).epsilon(1e-6));
  CHECK(px.tau.z == Approx(6.0).epsilon(1e-6));

  px.add_pass(4, Color(1, 0.5f, 0), alpha_f);
  by_hand(4, glm::dvec3(1, 0.5, 0));
  check("pass 2");
  // N = 8 + 8/3 = 32/3, f = (32/3) / 12 = 8/9.
  CHECK(px.n == Approx(32.0 / 3.0).epsilon(1e-6));
  CHECK(px.tau.x == Approx((2.0 + 1.0) * 8.0 / 9.0).epsilon(1e-6));

  // A pass without photons (no flux either) leaves everything as it was.
  const SppmPixel before = px;
  px.add_pass(0, Color(0.0f), alpha_f);
  CHECK(px.radius == before.radius);
  CHECK(px.n == before.n);
  CHECK(px.tau == before.tau);

  for (int i = 0; i < 20; ++i) {
    const double m = 1 + (i * 7) % 5;
    const glm::dvec3 phi(0.1 * i, 0.2, 1.0 / (i + 1));
    px.add_pass(size_t(m), Color(phi), alpha_f);
    by_hand(m, phi);
  }
  check("pass 22");

  // Another alpha: N' = N + 0.25 M.
  SppmPixel q;
  q.radius = 1.0f;
  q.add_pass(100, Color(1.0f), 0.25f);
  CHECK(q.n == Approx(25.0));
  CHECK(q.radius == Approx(0.5f).epsilon(1e-6));
  CHECK(q.tau.y == Approx(0.25).epsilon(1e-6));

  // In a medium (photons in a ball): r' = r cbrt(N' / (N + M)), and tau, radiance times pi r^2,
  // scales with the radius's square. N = 25 from 100 photons: r = cbrt(1/4), tau = 4^(-2/3).
  SppmPixel v;
  v.radius = 1.0f;
  v.add_pass(100, Color(1.0f, 2.0f, 0.0f), 0.25f, 3);
  CHECK(v.n == Approx(25.0));
  CHECK(v.radius == Approx(std::cbrt(0.25)).epsilon(1e-6));
  CHECK(v.tau.x == Approx(std::pow(0.25, 2.0 / 3.0)).epsilon(1e-6));
  CHECK(v.tau.y == Approx(2.0 * std::pow(0.25, 2.0 / 3.0)).epsilon(1e-6));
  // Each pass's phi is its radiance times pi r^2 at its radius: tau / (pi r^2) stays the sum of
  // the passes' radiances whatever the radius became.
  const double r1 = v.radius;
  v.add_pass(30, Color(float(kPi * r1 * r1) * 0.5f), 0.25f, 3);  // a radiance of 0.5
  CHECK(v.radius < r1);
  CHECK(v.tau.x / (double(kPi) * double(v.radius) * double(v.radius)) == Approx(1.0 / kPi + 0.5).epsilon(1e-5));
}

// ---- Consistency: the error keeps falling as passes are added -------------------------------

// Both progressive methods on the Cornell box with 2000 photons per pass, against a path-traced
// reference. The error is the relMSE of 8x8-pixel block means, so that what is measured is the
// photon estimates' bias and blotches rather than pixel noise (which any method loses by
// averaging passes); the emitter is hidden (hide_emitters) for the same reason: its edge's
// anti-aliasing error, the same for every integrator, would otherwise dominate the first passes.
// With this few photons the error is mostly the density estimates' bias, which falls with the
// radius: for bias ~ r, the block error falls as r^2, scale(63) / scale(3) = 0.40 from pass 4 to
// pass 64. Measured (seeds 12 to 15): progressive photon 0.24 to 0.43 (0.36 to 0.49 with the
// fixed radii it had before its discs became the k nearest photons' shrunk), sppm 0.34 to 0.37;
// the photon integrator with one pair of maps (not progressive) keeps its bias: 0.96 to 1.07.
// Tolerances: progressive photon < 0.6, sppm < 0.5, one pair of maps > 0.8.
TEST_CASE("progressive photon and sppm: block error after 64 passes below 0.6 and 0.5 x that after 4 (Cornell box)",
          "[trace][progressive][consistency]" TIER_FIGURE) {
  Job ref_job;
  ref_job.scene_text = test::read_scene_file("scenes/cornell-box.json");
  ref_job.integrator = "path";
  ref_job.settings = R"({"hide_emitters": true})";
  ref_job.spp = 512;
  ref_job.seed = 11;
  const Image ref = run(ref_job).image;

  Job job = ref_job;
  job.seed = 12;
  auto ratio = [&](const char* integrator, const char* settings, double& e4, double& e64) {
    job.integrator = integrator;
    job.settings = settings;
    const auto snaps = snapshots(job, {4, 64});
    e4 = block_relmse(snaps.at(4), ref, 8);
    e64 = block_relmse(snaps.at(64), ref, 8);
    return e64 / e4;
  };
  double e4, e64;
  const double ppm = ratio("photon", R"({"progressive": true, "photons": 2000, "caustic_photons": 2000, "hide_emitters": true})", e4, e64);
  INFO("progressive photon: block relMSE " << e4 << " after 4 passes, " << e64 << " after 64: ratio " << ppm);
  CHECK(ppm < 0.6);
  const double sppm = ratio("sppm", R"({"photons": 2000, "hide_emitters": true})", e4, e64);
  INFO("sppm: block relMSE " << e4 << " after 4 passes, " << e64 << " after 64: ratio " << sppm);
  CHECK(sppm < 0.5);
  // The control: one pair of maps for all passes is not consistent, and the measure shows it.
  const double fixed = ratio("photon", R"({"progressive": false, "photons": 2000, "caustic_photons": 2000, "hide_emitters": true})", e4, e64);
  INFO("photon, one pair of maps: block relMSE " << e4 << " after 4 passes, " << e64 << " after 64: ratio " << fixed);
  CHECK(fixed > 0.8);
}

// ---- Determinism -----------------------------------------------------------------------------

TEST_CASE("progressive photon and sppm: identical pixels for 1 and 2 threads", "[trace][progressive][determinism]" TIER_UNIT) {
  for (const auto& [name, settings] : {std::pair<std::string, std::string>{"photon", kProgressivePhoton},
                                       std::pair<std::string, std::string>{"sppm", kSmallSppm}}) {
    Job job;
    job.scene_text = test::read_scene_file("tests/data/tiny.json");
    job.integrator = name;
    job.settings = settings;
    job.width = job.height = 16;
    job.spp = 4;
    job.seed = 5;
    job.threads = 1;
    const Result one = run(job);
    job.threads = 2;
    const Result two = run(job);
    INFO(name);
    CHECK(one.stats.passes == 4);
    CHECK(image_mean(one.image).x > 0.01);
    CHECK(one.image.pixels == two.image.pixels);
    // Another seed is other noise: the passes' photon maps follow the seed.
    job.seed = 6;
    const Result other = run(job);
    CHECK(other.image.pixels != one.image.pixels);
  }
}

// ---- Analytic and reference values ------------------------------------------------------------

TEST_CASE("sppm: furnace reads Le / (1 - albedo) within 2 %", "[trace][sppm][furnace]" TIER_UNIT) {
  Job job;
  job.scene_text = test::furnace_scene(0.5, 1.0, R"({"type": "sppm"})");
  job.integrator = "sppm";
  job.settings = R"({"photons": 50000})";
  job.width = job.height = 24;
  job.spp = 8;
  const Result r = run(job);
  const glm::dvec3 mean = image_mean(r.image);
  INFO("mean " << mean.x << " " << mean.y << " " << mean.z);
  for (int c = 0; c < 3; ++c) CHECK(mean[c] == Approx(2.0).epsilon(0.02));
  CHECK(r.stats.bad_samples == 0);
}

// The emitter is hidden in both: at 32x32 its pixels are half the image mean, and the
// anti-aliasing of its edge after 16 passes moves the mean by up to 3 % from seed to seed.
// Measured (eight seeds): sppm 0.1 to 1.5 % below path with 100000 photons a pass (0.8 to 2 %
// with 50000: the bias of the radii, which shrinks with the photons).
TEST_CASE("sppm: image mean matches the path tracer on the Cornell box within 3 %", "[trace][sppm][reference]" TIER_FIGURE) {
  Job job;
  job.scene_text = test::read_scene_file("scenes/cornell-box.json");
  const glm::dvec3 path = image_mean(hidden_emitter_reference("cornell-box-32-hidden", job.scene_text, 2048, 32).image);
  const glm::dvec3 sppm = mean_with(job, "sppm", R"({"photons": 100000, "hide_emitters": true})", 16, 4);
  INFO("path " << path.x << " " << path.y << " " << path.z << "; sppm " << sppm.x << " " << sppm.y << " " << sppm.z);
  for (int c = 0; c < 3; ++c) CHECK(sppm[c] == Approx(path[c]).epsilon(0.03));
}

// photon (one pair of maps), sppm and path on the Cornell box with a mirror and a glass sphere:
// at every max_depth they count the same light paths (at most max_depth + 1 segments), so the
// means agree. The emitter is hidden from the camera in all three, as its edge's anti-aliasing
// would move the photon and sppm means by about 0.5 % at 64 passes. The path reference's mean
// varies by at most 0.35 % from seed to seed at 4096 spp.
// Measured (three seeds each): sppm -0.5 to +0.8 % from path; photon ran 0.3 to 1.9 % high
// while its k-NN estimate counted the k-th photon on the disc's rim (k / (k - 1), see
// tests/photon/density_test.cpp); both now get 1.5 %.
static void check_max_depth_agreement(int max_depth) {
  Job job;
  job.scene_text = test::read_scene_file("scenes/cornell-spheres.json");
  job.max_depth = max_depth;
  job.width = job.height = 24;
  nlohmann::json ref_scene = nlohmann::json::parse(job.scene_text);
  ref_scene["render"]["max_depth"] = max_depth;
  const glm::dvec3 path = image_mean(hidden_emitter_reference("cornell-spheres-24-hidden-depth" + std::to_string(max_depth),
                                                              ref_scene.dump(), 8192, 24, 21).image);
  const glm::dvec3 photon = mean_with(job, "photon", R"({"progressive": false, "hide_emitters": true})", 64, 22);
  const glm::dvec3 sppm = mean_with(job, "sppm", R"({"photons": 100000, "hide_emitters": true})", 48, 23);
  INFO("max_depth " << max_depth << ": path " << path.x << " " << path.y << " " << path.z << "; photon " << photon.x
                    << " " << photon.y << " " << photon.z << "; sppm " << sppm.x << " " << sppm.y << " " << sppm.z);
  for (int c = 0; c < 3; ++c) {
    CHECK(photon[c] == Approx(path[c]).epsilon(0.015));
    CHECK(sppm[c] == Approx(path[c]).epsilon(0.015));
  }
}

TEST_CASE("max_depth 2: photon and sppm within 1.5 % of path (Cornell spheres)",
          "[trace][progressive][max_depth]" TIER_FIGURE) {
  check_max_depth_agreement(2);
}

TEST_CASE("max_depth 3: photon and sppm within 1.5 % of path (Cornell spheres)",
          "[trace][progressive][max_depth]" TIER_FIGURE) {
  check_max_depth_agreement(3);
}

TEST_CASE("max_depth 9: photon and sppm within 1.5 % of path (Cornell spheres)",
          "[trace][progressive][max_depth]" TIER_FIGURE) {
  check_max_depth_agreement(9);
}

// ---- Pass control: time budget and cancellation ------------------------------------------------

TEST_CASE("progressive: a time budget stops between passes", "[trace][progressive][cancel]" TIER_UNIT) {
  for (const auto& [name, settings] : kProgressiveIntegrators) {
    INFO(name);
    Job job = cornell_box_job(name, settings);
    // A budget of at least four passes' time: under a sanitizer on a loaded CI machine a pass
    // took more than the fixed 0.25 s this test used to allow.
    job.spp = 1;
    const auto t0 = std::chrono::steady_clock::now();
    run(job);
    const double one_pass = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    job.spp = 4;  // as before: the time budget decides
    job.time_limit = std::max(0.5, 4.0 * one_pass);
    INFO("one pass " << one_pass << " s, budget " << job.time_limit << " s");
    int last_pass = 0;
    job.on_pass = [&](int passes, double, const Image&) { last_pass = passes; };
    const Result r = run(job);
    CHECK(r.stats.passes >= 2);
    CHECK(r.stats.passes == last_pass);
    CHECK_FALSE(r.stats.interrupted);
    CHECK(r.stats.samples == uint64_t(r.stats.passes) * 32 * 32);  // whole passes only
    CHECK(r.stats.seconds < job.time_limit + 1.5);
    CHECK(finite_non_negative(r.image));
    CHECK(image_mean(r.image).x > 0.05);
  }
}

TEST_CASE("progressive: a cancel set in on_pass stops before the next pass, the image is that of fewer passes",
          "[trace][progressive][cancel]" TIER_UNIT) {
  for (const auto& [name, settings] : kProgressiveIntegrators) {
    INFO(name);
    Job job = cornell_box_job(name, settings);
    job.spp = 3;
    const Result three = run(job);
    std::atomic<bool> cancel{false};
    job.spp = 1000;
    job.cancel = &cancel;
    job.on_pass = [&](int passes, double, const Image&) {
      if (passes == 3) cancel = true;
    };
    const Result r = run(job);
    CHECK(r.stats.interrupted);
    CHECK(r.stats.passes == 3);
    CHECK(r.stats.samples == 3u * 32 * 32);
    CHECK(finite_non_negative(r.image));
    CHECK(image_mean(r.image).x > 0.05);
    // The cancelled pass 4 left no trace: the image is the 3-pass render's.
    CHECK(r.image.pixels == three.image.pixels);
  }
}

TEST_CASE("progressive: a cancel from another thread stops the render, counting whole passes",
          "[trace][progressive][cancel]" TIER_UNIT) {
  for (const auto& [name, settings] : kProgressiveIntegrators) {
    INFO(name);
    Job job = cornell_box_job(name, settings);
    job.spp = 100000;  // minutes if not stopped
    std::atomic<bool> cancel{false};
    std::atomic<int> passes_done{0};
    job.cancel = &cancel;
    job.on_pass = [&](int passes, double, const Image&) { passes_done = passes; };
    std::thread stopper([&] {
      const auto start = std::chrono::steady_clock::now();
      while (passes_done.load() < 2 && std::chrono::steady_clock::now() - start < std::chrono::seconds(20)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(30));
      cancel = true;
    });
    const auto t0 = std::chrono::steady_clock::now();
    const Result r = run(job);
    stopper.join();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    CHECK(seconds < 5.0);
    CHECK(r.stats.interrupted);
    CHECK(r.stats.passes >= 2);
    CHECK(r.stats.passes == passes_done.load());
    // Whole passes, and at most part of one more (each pixel is the mean of its own passes).
    CHECK(r.stats.samples >= uint64_t(r.stats.passes) * 32 * 32);
    CHECK(r.stats.samples < uint64_t(r.stats.passes + 1) * 32 * 32);
    CHECK(finite_non_negative(r.image));
    CHECK(image_mean(r.image).x > 0.05);
  }
}
