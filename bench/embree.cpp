// The same ray batches through Embree 3 (single-ray API), as the reference for this CPU.
// Built only when Embree is installed (Debian libembree-dev); used nowhere but bench/.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include "bench_util.h"

using namespace caustica;
using namespace caustica::bench;

namespace {

struct EmbreeScene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  explicit EmbreeScene(const Scene& s) {
    device = rtcNewDevice("threads=1");
    scene = rtcNewScene(device);
    // As Caustica's backend builds it (src/core/embree_accel.cpp), so that the comparison
    // measures our interface, not the settings.
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    const auto& prims = s.accel().primitives();
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), 3 * prims.size()));
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(unsigned), prims.size()));
    for (size_t i = 0; i < prims.size(); ++i) {
      const Vec3 p[3] = {prims[i].p0, prims[i].p1, prims[i].p2};
      for (int k = 0; k < 3; ++k) {
        v[9 * i + 3 * k + 0] = p[k].x;
        v[9 * i + 3 * k + 1] = p[k].y;
        v[9 * i + 3 * k + 2] = p[k].z;
        idx[3 * i + k] = unsigned(3 * i + k);
      }
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
  }
  ~EmbreeScene() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
  // One raw rtcIntersect1 (closest hit) or rtcOccluded1 (shadow): whether the ray hit.
  bool cast(const Ray& ray, bool shadow) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray.org_x = ray.origin.x;
    rh.ray.org_y = ray.origin.y;
    rh.ray.org_z = ray.origin.z;
    rh.ray.dir_x = ray.dir.x;
    rh.ray.dir_y = ray.dir.y;
    rh.ray.dir_z = ray.dir.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = ray.tmax;
    rh.ray.mask = ~0u;
    rh.ray.flags = 0;
    rh.ray.time = 0;
    if (shadow) {
      rtcOccluded1(scene, &ctx, &rh.ray);
      return rh.ray.tfar < 0.0f;
    }
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx, &rh);
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
  }
};

// args: shadow (0/1), threads
void BM_EmbreeRays(benchmark::State& state) {
  const Scene* s = bunny();
  if (!s) return state.SkipWithError("bunny.obj missing (install glmark2-data)");
  static EmbreeScene es(*s);
  const bool shadow = state.range(0) != 0;
  const RayBatch batch = make_rays(*s, 1 << 20, shadow, 7);
  tbb::global_control c(tbb::global_control::max_allowed_parallelism, size_t(state.range(1)));
  size_t hits = 0;
  for (auto _ : state) {
    hits = count_hits(batch.rays, [&](const Ray& ray) { return es.cast(ray, shadow); });
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(batch.rays.size()));
  state.counters["hit_fraction"] = double(hits) / double(batch.rays.size());
  state.SetLabel(std::string("embree bunny") + (shadow ? " shadow" : " closest"));
}
BENCHMARK(BM_EmbreeRays)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

// args: threads. The path tracer's own rays on cornell-bunny (1 spp, closest hits and shadow
// rays in the order it cast them) through raw Embree, in blocks of 4096 consecutive rays: the
// ray casting alone. samples_per_second is the recorded render's camera samples over that
// time, the most a path tracer on Embree could reach if everything but ray casting were free
// (compare BM_PathRender, measured in the same run).
void BM_PathRaysEmbree(benchmark::State& state) {
  const PathRays* recorded = cornell_bunny_path_rays();
  if (!recorded) return state.SkipWithError("bunny.obj missing (install glmark2-data)");
  static EmbreeScene es(recorded->scene());
  const auto& rays = recorded->rays;
  tbb::global_control c(tbb::global_control::max_allowed_parallelism, size_t(state.range(0)));
  size_t hits = 0;
  for (auto _ : state) hits = count_hits(rays, [&](const RecordedRay& r) { return es.cast(r.ray, r.shadow); });
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(rays.size()));
  state.counters["samples_per_second"] =
      benchmark::Counter(double(recorded->samples) * double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["rays_per_sample"] = double(rays.size()) / double(recorded->samples);
  state.counters["hit_fraction"] = double(hits) / double(rays.size());
  state.SetLabel("cornell-bunny path rays, raw embree");
}
BENCHMARK(BM_PathRaysEmbree)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
