// Benchmark set-up, cached across benchmarks.
#include "bench_util.h"
#include <filesystem>
#include <map>
#include <memory>
#include "core/rng.h"
#include "core/sampling.h"
#include <mutex>
#include <tbb/global_control.h>
#include "photon/photon_tracer.h"
#include "trace/integrator.h"
#include "trace/render.h"

namespace caustica::bench {

std::string source_dir() { return CAUSTICA_SOURCE_DIR; }

const Scene* cornell_spheres() {
  static LoadedScene s = load_scene(source_dir() + "/scenes/cornell-spheres.json");
  return s.scene.get();
}

const Scene* bunny() {
  static std::unique_ptr<LoadedScene> s = [] {
    const std::string obj = "/usr/share/glmark2/models/bunny.obj";
    if (!std::filesystem::exists(obj)) return std::unique_ptr<LoadedScene>();
    const std::string text = R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0]},
      "materials": {"white": {"type": "diffuse", "albedo": 0.8}},
      "objects": [{"type": "mesh", "file": ")" + obj + R"(", "material": "white"}]})";
    return std::make_unique<LoadedScene>(parse_scene(text, "bunny.json", "/"));
  }();
  return s ? s->scene.get() : nullptr;
}

RayBatch make_rays(const Scene& scene, size_t n, bool shadow, uint64_t seed) {
  Rng rng(seed);
  const Bounds b = scene.accel().bounds();
  const Vec3 c = b.centre();
  const float r = 0.5f * glm::length(b.extent());
  RayBatch batch;
  batch.rays.reserve(n);
  auto inside = [&] {
    const float x = rng.next_float(), y = rng.next_float(), z = rng.next_float();
    return b.lo + Vec3(x, y, z) * b.extent();
  };
  for (size_t i = 0; i < n; ++i) {
    // Origins inside the bounds (a room seen from within) or on a sphere around a mesh.
    const float u = rng.next_float(), v = rng.next_float();
    const Vec3 o = scene.lights.empty() ? c + 1.5f * r * sample_uniform_sphere(Vec2(u, v)) : inside();
    const Vec3 target = inside();
    const Vec3 d = target - o;
    const float len = glm::length(d);
    batch.rays.push_back(Ray{o, d / len, shadow ? len : kInfinity});
  }
  return batch;
}

namespace {
// Casts through another accelerator and appends every ray to a list.
class RecordingAccel final : public Accelerator {
 public:
  RecordingAccel(std::unique_ptr<Accelerator> inner, std::vector<RecordedRay>& out)
      : inner_(std::move(inner)), out_(out) {}
  bool intersect(const Ray& ray, Hit& hit) const override {
    record(ray, false);
    return inner_->intersect(ray, hit);
  }
  bool occluded(const Ray& ray) const override {
    record(ray, true);
    return inner_->occluded(ray);
  }
  const std::vector<Primitive>& primitives() const override { return inner_->primitives(); }
  Bounds bounds() const override { return inner_->bounds(); }
  size_t memory_bytes() const override { return inner_->memory_bytes(); }
  const char* name() const override { return inner_->name(); }
  std::unique_ptr<Accelerator> release() { return std::move(inner_); }

 private:
  void record(const Ray& ray, bool shadow) const {
    std::lock_guard<std::mutex> lock(mutex_);
    out_.push_back(RecordedRay{ray, shadow});
  }
  std::unique_ptr<Accelerator> inner_;
  std::vector<RecordedRay>& out_;
  mutable std::mutex mutex_;
};
}  // namespace

const PathRays* cornell_bunny_path_rays() {
  static std::unique_ptr<PathRays> recorded = []() -> std::unique_ptr<PathRays> {
    if (!std::filesystem::exists("/usr/share/glmark2/models/bunny.obj")) return nullptr;
    auto p = std::make_unique<PathRays>();
    p->loaded = std::make_unique<LoadedScene>(load_scene(source_dir() + "/scenes/cornell-bunny.json"));
    Scene& scene = p->scene();
    scene.wrap_accel([&](std::unique_ptr<Accelerator> a) { return std::make_unique<RecordingAccel>(std::move(a), p->rays); });
    const auto integrator = create_integrator("path", p->loaded->integrator_settings, scene.render);
    RenderOptions options;
    options.job.passes = 1;
    options.quiet = true;
    RenderStats stats;
    {
      tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
      render_image(scene, *integrator, options, stats);
    }
    p->samples = stats.samples;
    scene.wrap_accel([](std::unique_ptr<Accelerator> a) { return static_cast<RecordingAccel&>(*a).release(); });
    return p;
  }();
  return recorded.get();
}

const std::vector<Photon>& cornell_photons(size_t n) {
  static std::vector<Photon> photons;
  if (photons.size() < n) {
    PhotonPassSettings s;
    s.global_photons = n;
    s.caustic_photons = 0;
    photons = trace_photons(*cornell_spheres(), s).global;
  }
  return photons;
}

}  // namespace caustica::bench
