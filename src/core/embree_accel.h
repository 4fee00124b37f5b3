// Ray casting through Embree 3 (Debian libembree-dev): triangles as Embree triangle geometry,
// spheres and SDF grid voxels as user geometry calling our own tests (intersect_primitive: the
// double-precision sphere, the SDF voxel's cubic), so that both backends find the same hits;
// round linear curves as Embree's own curve geometry (our BVH's test is its oracle).
// Built only with CAUSTICA_EMBREE.
#pragma once
#ifdef CAUSTICA_EMBREE
#include <atomic>
#include <embree3/rtcore.h>
#include "core/accel.h"

namespace caustica {

class EmbreeAccel final : public Accelerator {
 public:
  explicit EmbreeAccel(std::vector<Primitive> prims);
  ~EmbreeAccel() override;
  EmbreeAccel(const EmbreeAccel&) = delete;
  EmbreeAccel& operator=(const EmbreeAccel&) = delete;

  bool intersect(const Ray& ray, Hit& hit) const override;
  bool occluded(const Ray& ray) const override;
  const std::vector<Primitive>& primitives() const override { return prims_; }
  Bounds bounds() const override { return bounds_; }
  size_t memory_bytes() const override { return size_t(std::max<int64_t>(0, memory_.load())); }
  const char* name() const override { return "embree"; }

 private:
  std::vector<Primitive> prims_;
  std::vector<uint32_t> triangles_, user_, curves_, splines_;  // Embree primID -> index into prims_, per geometry
  std::vector<Primitive> user_prims_;       // spheres and SDF voxels in primID order, for the callbacks
  Bounds bounds_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  unsigned user_geometry_ = RTC_INVALID_GEOMETRY_ID, curve_geometry_ = RTC_INVALID_GEOMETRY_ID,
           spline_geometry_ = RTC_INVALID_GEOMETRY_ID;
  std::atomic<int64_t> memory_{0};
};

}  // namespace caustica
#endif
