// Embree 3 backend; see embree_accel.h.
#ifdef CAUSTICA_EMBREE
#include "core/embree_accel.h"
#include <algorithm>
#include <functional>
#include <cmath>
#include "core/error.h"

namespace caustica {
namespace {

// User geometry: the spheres and SDF voxels, in Embree's primID order, tested as our BVH tests
// them (intersect_primitive).
void user_bounds(const RTCBoundsFunctionArguments* args) {
  const Primitive& p = static_cast<const Primitive*>(args->geometryUserPtr)[args->primID];
  const Bounds b = p.bounds();
  args->bounds_o->lower_x = b.lo.x, args->bounds_o->lower_y = b.lo.y, args->bounds_o->lower_z = b.lo.z;
  args->bounds_o->upper_x = b.hi.x, args->bounds_o->upper_y = b.hi.y, args->bounds_o->upper_z = b.hi.z;
}

Ray to_ray(const RTCRay& r) {
  return Ray{Vec3(r.org_x, r.org_y, r.org_z), Vec3(r.dir_x, r.dir_y, r.dir_z), r.tfar};
}

void user_intersect(const RTCIntersectFunctionNArguments* args) {
  // rtcIntersect1 only: N is 1.
  if (!args->valid[0]) return;
  RTCRayHit* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
  const Primitive& p = static_cast<const Primitive*>(args->geometryUserPtr)[args->primID];
  float t;
  if (!intersect_primitive(to_ray(rh->ray), p, rh->ray.tfar, t) || !(t > rh->ray.tnear)) return;
  rh->ray.tfar = t;
  rh->hit.geomID = args->geomID;
  rh->hit.primID = args->primID;
  rh->hit.instID[0] = args->context->instID[0];
}

void user_occluded(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  RTCRay* r = reinterpret_cast<RTCRay*>(args->ray);
  const Primitive& p = static_cast<const Primitive*>(args->geometryUserPtr)[args->primID];
  float t;
  if (intersect_primitive(to_ray(*r), p, r->tfar, t) && t > r->tnear) r->tfar = -INFINITY;
}

// Curves' backfaces are culled (Embree 3 reports a ray leaving a curve it started in; our BVH,
// Embree 4 and Mitsuba do not): a hit whose normal faces along the ray is passed over.
void cull_curve_backface(const RTCFilterFunctionNArguments* args) {
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const float along = RTCRayN_dir_x(args->ray, args->N, i) * RTCHitN_Ng_x(args->hit, args->N, i) +
                        RTCRayN_dir_y(args->ray, args->N, i) * RTCHitN_Ng_y(args->hit, args->N, i) +
                        RTCRayN_dir_z(args->ray, args->N, i) * RTCHitN_Ng_z(args->hit, args->N, i);
    if (along > 0.0f) args->valid[i] = 0;
  }
}

bool track_memory(void* user, ssize_t bytes, bool) {
  static_cast<std::atomic<int64_t>*>(user)->fetch_add(int64_t(bytes), std::memory_order_relaxed);
  return true;
}

void fill_ray(const Ray& ray, RTCRay& r) {
  r.org_x = ray.origin.x, r.org_y = ray.origin.y, r.org_z = ray.origin.z;
  r.dir_x = ray.dir.x, r.dir_y = ray.dir.y, r.dir_z = ray.dir.z;
  r.tnear = 0.0f;
  r.tfar = ray.tmax;
  r.time = 0.0f;
  r.mask = ~0u;
  r.id = 0;
  r.flags = 0;
}

}  // namespace

EmbreeAccel::EmbreeAccel(std::vector<Primitive> prims) : prims_(std::move(prims)) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw InputError("Embree: cannot create a device (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
  rtcSetDeviceMemoryMonitorFunction(device_, track_memory, &memory_);
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  auto attach = [&](RTCGeometry g, unsigned id) {
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene_, g, id);
    rtcReleaseGeometry(g);
  };
  for (uint32_t i = 0; i < prims_.size(); ++i) {
    switch (prims_[i].kind) {
      case ShapeKind::Triangle: triangles_.push_back(i); break;
      case ShapeKind::LinearCurve: curves_.push_back(i); break;
      case ShapeKind::BsplineCurve: splines_.push_back(i); break;
      default: user_.push_back(i); break;
    }
    bounds_.extend(prims_[i].bounds());
  }
  if (!triangles_.empty()) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), 3 * triangles_.size()));
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles_.size()));
    for (size_t i = 0; i < triangles_.size(); ++i) {
      const Primitive& p = prims_[triangles_[i]];
      const Vec3 corners[3] = {p.p0, p.p1, p.p2};
      for (int k = 0; k < 3; ++k) {
        for (int c = 0; c < 3; ++c) v[9 * i + 3 * size_t(k) + size_t(c)] = corners[k][c];
        idx[3 * i + size_t(k)] = unsigned(3 * i + size_t(k));
      }
    }
    attach(g, 0);
  }
  if (!user_.empty()) {
    user_prims_.reserve(user_.size());
    for (uint32_t i : user_) user_prims_.push_back(prims_[i]);
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, unsigned(user_.size()));
    rtcSetGeometryUserData(g, user_prims_.data());
    rtcSetGeometryBoundsFunction(g, user_bounds, nullptr);
    rtcSetGeometryIntersectFunction(g, user_intersect);
    rtcSetGeometryOccludedFunction(g, user_occluded);
    user_geometry_ = 1;
    attach(g, user_geometry_);
  }
  // Embree's round curves: each segment its own control points (x, y, z, radius), so that no
  // segment has neighbours and each is the whole sweep our BVH's test intersects; backfaces culled.
  auto curve_geometry = [&](RTCGeometryType type, const std::vector<uint32_t>& ids, size_t per_segment,
                            const std::function<void(const Primitive&, float*)>& write) {
    RTCGeometry g = rtcNewGeometry(device_, type);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                          4 * sizeof(float), per_segment * ids.size()));
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), ids.size()));
    for (size_t i = 0; i < ids.size(); ++i) {
      write(prims_[ids[i]], v + 4 * per_segment * i);
      idx[i] = unsigned(per_segment * i);
    }
    rtcSetGeometryIntersectFilterFunction(g, cull_curve_backface);
    rtcSetGeometryOccludedFilterFunction(g, cull_curve_backface);
    return g;
  };
  if (!curves_.empty()) {
    RTCGeometry g = curve_geometry(RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE, curves_, 2, [](const Primitive& p, float* v) {
      const float cp[8] = {p.p0.x, p.p0.y, p.p0.z, p.p2.x, p.p1.x, p.p1.y, p.p1.z, p.p2.y};
      std::copy(cp, cp + 8, v);
    });
    // No neighbours (flags 0): each segment keeps both end spheres.
    auto* flags = static_cast<unsigned char*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_FLAGS, 0, RTC_FORMAT_UCHAR, 1, curves_.size()));
    std::fill(flags, flags + curves_.size(), static_cast<unsigned char>(0));
    curve_geometry_ = 2;
    attach(g, curve_geometry_);
  }
  if (!splines_.empty()) {
    RTCGeometry g = curve_geometry(RTC_GEOMETRY_TYPE_ROUND_BSPLINE_CURVE, splines_, 4, [](const Primitive& p, float* v) {
      const glm::vec4* cp = p.bspline_points();
      for (int k = 0; k < 4; ++k)
        for (int c = 0; c < 4; ++c) v[4 * k + c] = cp[k][c];
    });
    spline_geometry_ = 3;
    attach(g, spline_geometry_);
  }
  rtcCommitScene(scene_);
  const RTCError e = rtcGetDeviceError(device_);
  if (e != RTC_ERROR_NONE) throw InputError("Embree: building the scene failed (error " + std::to_string(int(e)) + ")");
}

EmbreeAccel::~EmbreeAccel() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

bool EmbreeAccel::intersect(const Ray& ray, Hit& hit) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  fill_ray(ray, rh.ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit.t = rh.ray.tfar;
  hit.prim = rh.hit.geomID == user_geometry_    ? user_[rh.hit.primID]
             : rh.hit.geomID == curve_geometry_ ? curves_[rh.hit.primID]
             : rh.hit.geomID == spline_geometry_ ? splines_[rh.hit.primID]
                                                : triangles_[rh.hit.primID];
  return true;
}

bool EmbreeAccel::occluded(const Ray& ray) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r;
  fill_ray(ray, r);
  rtcOccluded1(scene_, &ctx, &r);
  return r.tfar < 0.0f;
}

}  // namespace caustica
#endif
