// Kernel benchmarks: ray casting (ours and Embree's), BVH build, photon pass, kd-tree build
// and queries, final gathering. Reproduce with: bash scripts/bench.sh (see BENCHMARKS.md).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include "bench_util.h"
#include "core/rng.h"
#include "photon/photon_tracer.h"
#include "trace/photon_integrator.h"
#include "trace/render.h"

using namespace caustica;
using namespace caustica::bench;

namespace {

const Scene* scene_by_index(int i) { return i == 0 ? cornell_spheres() : bunny(); }
const char* scene_name(int i) { return i == 0 ? "cornell-spheres" : "bunny"; }

// The scene's primitives behind one backend (0 our BVH, 1 Embree), built once per scene.
const Accelerator* backend(int scene, int kind) {
  static std::unique_ptr<Accelerator> cache[2][2];
  std::unique_ptr<Accelerator>& a = cache[scene][kind];
  if (!a) a = make_accelerator(kind == 0 ? AccelKind::Bvh : AccelKind::Embree, scene_by_index(scene)->accel().primitives());
  return a.get();
}

// args: scene (0 cornell-spheres, 1 bunny), shadow (0/1), threads, backend (0 bvh, 1 embree):
// rays through Caustica's ray-casting interface (Accelerator), to compare with BM_EmbreeRays.
void BM_Rays(benchmark::State& state) {
  const Scene* scene = scene_by_index(int(state.range(0)));
  if (!scene) return state.SkipWithError("bunny.obj missing (install glmark2-data)");
  if (state.range(3) == 1 && !embree_available()) return state.SkipWithError("built without Embree");
  const Accelerator* accel = backend(int(state.range(0)), int(state.range(3)));
  const bool shadow = state.range(1) != 0;
  const RayBatch batch = make_rays(*scene, 1 << 20, shadow, 7);
  tbb::global_control c(tbb::global_control::max_allowed_parallelism, size_t(state.range(2)));
  size_t hits = 0;
  for (auto _ : state) {
    hits = shadow ? count_hits(batch.rays, [&](const Ray& ray) { return accel->occluded(ray); })
                  : count_hits(batch.rays, [&](const Ray& ray) {
                      Hit hit;
                      return accel->intersect(ray, hit);
                    });
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(batch.rays.size()));
  state.counters["hit_fraction"] = double(hits) / double(batch.rays.size());
  state.SetLabel(std::string(scene_name(int(state.range(0)))) + (shadow ? " shadow " : " closest ") + accel->name());
}
BENCHMARK(BM_Rays)->ArgsProduct({{0, 1}, {0, 1}, {1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();

// args: backend (0 bvh, 1 embree), threads. The path tracer on cornell-bunny at 1 spp (the render
// whose rays BM_PathRaysEmbree replays): samples/s end to end, to hold against that bound.
void BM_PathRender(benchmark::State& state) {
  const PathRays* recorded = cornell_bunny_path_rays();
  if (!recorded) return state.SkipWithError("bunny.obj missing (install glmark2-data)");
  if (state.range(0) == 1 && !embree_available()) return state.SkipWithError("built without Embree");
  Scene& scene = recorded->scene();
  scene.set_accel(state.range(0) == 0 ? AccelKind::Bvh : AccelKind::Embree);
  const auto integrator = create_integrator("path", recorded->loaded->integrator_settings, scene.render);
  RenderOptions options;
  options.job.passes = 1;
  options.quiet = true;
  tbb::global_control c(tbb::global_control::max_allowed_parallelism, size_t(state.range(1)));
  RenderStats stats;
  for (auto _ : state) benchmark::DoNotOptimize(render_image(scene, *integrator, options, stats));
  state.counters["samples_per_second"] =
      benchmark::Counter(double(stats.samples) * double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["rays_per_sample"] = double(stats.rays) / double(stats.samples);
  state.SetLabel(std::string("cornell-bunny path, ") + scene.accel().name());
}
BENCHMARK(BM_PathRender)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_BvhBuild(benchmark::State& state) {
  const Scene* scene = bunny();
  if (!scene) return state.SkipWithError("bunny.obj missing (install glmark2-data)");
  const std::vector<Primitive> prims = scene->accel().primitives();
  for (auto _ : state) {
    Bvh bvh;
    bvh.build(prims);
    benchmark::DoNotOptimize(bvh.node_count());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(prims.size()));
  state.SetLabel("bunny, " + std::to_string(prims.size()) + " triangles");
}
BENCHMARK(BM_BvhBuild)->Unit(benchmark::kMillisecond);

// args: caustic (0 global, 1 caustic), threads
void BM_PhotonPass(benchmark::State& state) {
  const Scene* scene = cornell_spheres();
  const bool caustic = state.range(0) != 0;
  tbb::global_control c(tbb::global_control::max_allowed_parallelism, size_t(state.range(1)));
  PhotonPassSettings s;
  s.global_photons = caustic ? 0 : 1000000;
  s.caustic_photons = caustic ? 1000000 : 0;
  size_t stored = 0;
  for (auto _ : state) {
    const PhotonPassResult r = trace_photons(*scene, s);
    stored = r.global.size() + r.caustic.size();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(stored));
  state.SetLabel(std::string(caustic ? "caustic" : "global") + " photons stored, cornell-spheres");
}
BENCHMARK(BM_PhotonPass)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

// args: photons, leaf size
void BM_KdTreeBuild(benchmark::State& state) {
  const size_t n = size_t(state.range(0));
  const std::vector<Photon> source(cornell_photons(n).begin(), cornell_photons(n).begin() + long(n));
  size_t bytes = 0;
  for (auto _ : state) {
    PhotonMap map;
    map.build(source, 1.0f, size_t(state.range(1)));
    bytes = map.memory_bytes();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(n));
  state.counters["bytes_per_photon"] = double(bytes) / double(n);
}
BENCHMARK(BM_KdTreeBuild)
    ->ArgsProduct({{100000, 250000, 1000000, 4000000}, {32}})
    ->ArgsProduct({{1000000}, {8, 16, 64}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// args: k (0 = radius query), leaf size
void BM_KdTreeQuery(benchmark::State& state) {
  const size_t n = 1000000;
  PhotonMap map;
  map.build(std::vector<Photon>(cornell_photons(n).begin(), cornell_photons(n).begin() + long(n)), 1.0f,
            size_t(state.range(1)));
  // Queries at other photons' positions: where lookups happen in a render.
  Rng rng(3);
  std::vector<Vec3> queries(4096);
  for (Vec3& q : queries) q = map[uint32_t(rng.next_u32() % n)].position + Vec3(0.5f, 0.0f, -0.5f);
  std::vector<Neighbour> out;
  const size_t k = size_t(state.range(0));
  size_t i = 0, found = 0;
  for (auto _ : state) {
    const Vec3& q = queries[i++ & 4095];
    found += k > 0 ? map.knn(q, k, 50.0f, out) : map.radius_query(q, 10.0f, out);
  }
  state.SetItemsProcessed(int64_t(state.iterations()));
  state.counters["found"] = double(found) / double(state.iterations());
  state.SetLabel(k > 0 ? "k-NN within 50, 1M photons" : "radius 10, 1M photons");
}
BENCHMARK(BM_KdTreeQuery)->ArgsProduct({{50, 100, 0}, {32}})->ArgsProduct({{50}, {8, 16, 64}});

// args: irradiance stride (0 = off)
void BM_FinalGather(benchmark::State& state) {
  Scene& scene = const_cast<Scene&>(*cornell_spheres());
  const int size = 64;
  scene.camera.set_resolution(size, size);
  JsonSource settings;
  settings.value = {{"photons", 200000}, {"caustic_photons", 0}, {"gather_rays", 32},
                    {"irradiance_stride", state.range(0)}};
  const std::unique_ptr<Integrator> made = create_integrator("photon", settings, scene.render);
  Integrator& integrator = *made;
  integrator.preprocess(scene, {0, true});
  RenderOptions options;
  options.job.passes = 1;
  options.quiet = true;
  for (auto _ : state) {
    RenderStats stats;
    benchmark::DoNotOptimize(render_image(scene, integrator, options, stats));
  }
  scene.camera.set_resolution(scene.render.width, scene.render.height);
  state.SetItemsProcessed(int64_t(state.iterations()) * size * size);
  state.SetLabel(state.range(0) > 0 ? "pixels, precomputed irradiance" : "pixels, full k-NN estimate");
}
BENCHMARK(BM_FinalGather)->Arg(4)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
