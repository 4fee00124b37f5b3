// The same ray batches through Embree 3 (single-ray API), as the reference for this CPU.
// Built only when Embree is installed (Debian libembree-dev); used nowhere but bench/.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include "bench_util.h"
#include "core/rng.h"
#include "core/sampling.h"

using namespace caustica;
using namespace caustica::bench;

namespace {

// A ray for rtcIntersect1/rtcOccluded1, with no hit yet.
RTCRayHit to_rayhit(const Ray& ray) {
  RTCRayHit rh;
  rh.ray.org_x = ray.origin.x, rh.ray.org_y = ray.origin.y, rh.ray.org_z = ray.origin.z;
  rh.ray.dir_x = ray.dir.x, rh.ray.dir_y = ray.dir.y, rh.ray.dir_z = ray.dir.z;
  rh.ray.tnear = 0.0f, rh.ray.tfar = ray.tmax, rh.ray.time = 0.0f;
  rh.ray.mask = ~0u, rh.ray.id = 0, rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

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
    RTCRayHit rh = to_rayhit(ray);
    if (shadow) {
      rtcOccluded1(scene, &ctx, &rh.ray);
      return rh.ray.tfar < 0.0f;
    }
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

// Final-gather rays as the photon integrator casts them: `group` cosine-distributed rays from
// each first hit of a camera ray on cornell-bunny (one ray per pixel), consecutive in the list.
std::vector<Ray> gather_groups(const Scene& s, int group) {
  std::vector<Ray> rays;
  Rng rng(11);
  const int w = s.camera.width(), h = s.camera.height();
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      SurfaceHit hit;
      if (!s.intersect(s.camera.generate_ray(x, y, Vec2(0.5f)), hit)) continue;
      for (int i = 0; i < group; ++i) {
        const Vec3 wi = hit.frame.to_world(sample_cosine_hemisphere(Vec2(rng.next_float(), rng.next_float())));
        rays.push_back(spawn_ray(hit.p, hit.n, wi));
      }
    }
  }
  return rays;
}

constexpr int kGather = 12;  // PhotonSettings::gather_rays' default

// One group of kGather rays by `mode`: 0 rtcIntersect1 each, 1 a 16-wide packet (12 lanes
// valid), 2 a stream (rtcIntersect1M) flagged coherent, 3 the stream flagged incoherent.
// Writes each ray's hit distance (infinity for a miss).
void cast_group(const EmbreeScene& es, const Ray* rays, int mode, float* t) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  if (mode == 1) {
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[16];
    for (int i = 0; i < 16; ++i) {
      const Ray& r = rays[std::min(i, kGather - 1)];
      valid[i] = i < kGather ? -1 : 0;
      rh.ray.org_x[i] = r.origin.x, rh.ray.org_y[i] = r.origin.y, rh.ray.org_z[i] = r.origin.z;
      rh.ray.dir_x[i] = r.dir.x, rh.ray.dir_y[i] = r.dir.y, rh.ray.dir_z[i] = r.dir.z;
      rh.ray.tnear[i] = 0.0f, rh.ray.tfar[i] = r.tmax, rh.ray.time[i] = 0.0f;
      rh.ray.mask[i] = ~0u, rh.ray.id[i] = unsigned(i), rh.ray.flags[i] = 0;
      rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, es.scene, &ctx, &rh);
    for (int i = 0; i < kGather; ++i) t[i] = rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID ? kInfinity : rh.ray.tfar[i];
    return;
  }
  RTCRayHit rh[kGather];
  for (int i = 0; i < kGather; ++i) rh[i] = to_rayhit(rays[i]);
  if (mode == 0) {
    for (int i = 0; i < kGather; ++i) rtcIntersect1(es.scene, &ctx, &rh[i]);
  } else {
    ctx.flags = mode == 2 ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    rtcIntersect1M(es.scene, &ctx, rh, kGather, sizeof(RTCRayHit));
  }
  for (int i = 0; i < kGather; ++i) t[i] = rh[i].hit.geomID == RTC_INVALID_GEOMETRY_ID ? kInfinity : rh[i].ray.tfar;
}

// args: mode (cast_group), threads. Whether Embree's packet or stream calls cast a point's
// final-gather rays faster than single rays; the rays and their hits are the same in every mode
// (checked against mode 0 before timing).
void BM_GatherRaysEmbree(benchmark::State& state) {
  const PathRays* recorded = cornell_bunny_path_rays();
  if (!recorded) return state.SkipWithError("bunny.obj missing (install glmark2-data)");
  static EmbreeScene es(recorded->scene());
  static const std::vector<Ray> rays = gather_groups(recorded->scene(), kGather);
  const int mode = int(state.range(0));
  const size_t groups = rays.size() / kGather;
  for (size_t g = 0; g < groups; g += 97) {
    float a[kGather], b[kGather];
    cast_group(es, &rays[g * kGather], 0, a);
    cast_group(es, &rays[g * kGather], mode, b);
    for (int i = 0; i < kGather; ++i) {
      if (!(a[i] == b[i] || std::abs(a[i] - b[i]) <= 1e-4f * a[i])) return state.SkipWithError("hits differ from rtcIntersect1's");
    }
  }
  tbb::global_control c(tbb::global_control::max_allowed_parallelism, size_t(state.range(1)));
  std::atomic<size_t> hits{0};
  for (auto _ : state) {
    hits = 0;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, groups, 256), [&](const tbb::blocked_range<size_t>& r) {
      size_t local = 0;
      for (size_t g = r.begin(); g != r.end(); ++g) {
        float t[kGather];
        cast_group(es, &rays[g * kGather], mode, t);
        for (float ti : t) local += ti < kInfinity ? 1 : 0;
      }
      hits += local;
    });
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(groups * kGather));
  state.counters["hit_fraction"] = double(hits.load()) / double(groups * kGather);
  static const char* names[] = {"rtcIntersect1", "rtcIntersect16 (12 lanes)", "rtcIntersect1M coherent", "rtcIntersect1M incoherent"};
  state.SetLabel(std::string("cornell-bunny gather groups of 12, ") + names[mode]);
}
BENCHMARK(BM_GatherRaysEmbree)->ArgsProduct({{0, 1, 2, 3}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
