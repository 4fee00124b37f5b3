// Benchmark set-up, cached across benchmarks.
#include "bench_util.h"
#include <filesystem>
#include <map>
#include <memory>
#include "core/rng.h"
#include "core/sampling.h"
#include "photon/photon_tracer.h"

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
