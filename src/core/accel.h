// Ray casting behind one interface: our own BVH (bvh.h, portable, the test oracle) or Embree 3
// (embree_accel.h, built with CAUSTICA_EMBREE). Hit::prim indexes primitives().
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include "core/shape.h"

namespace caustica {

struct Hit {
  float t = kInfinity;
  uint32_t prim = 0;
};

class Accelerator {
 public:
  virtual ~Accelerator() = default;
  virtual bool intersect(const Ray& ray, Hit& hit) const = 0;  // closest hit with 0 < t < ray.tmax
  virtual bool occluded(const Ray& ray) const = 0;             // any hit with 0 < t < ray.tmax
  virtual const std::vector<Primitive>& primitives() const = 0;
  virtual Bounds bounds() const = 0;
  virtual size_t memory_bytes() const = 0;  // the acceleration structure's own memory
  virtual const char* name() const = 0;
};

enum class AccelKind { Bvh, Embree };

// "bvh" or "embree"; false for anything else.
bool parse_accel(const std::string& name, AccelKind& kind);
// Embree when this build has it, else our BVH.
AccelKind default_accel();
bool embree_available();
// The one place that decides the backend: `requested`, or with none the default. Embree asked
// for in a build without it gives our BVH and sets `fell_back` (the scene reader warns; the
// command line's --accel embree is refused before it gets here).
AccelKind choose_accel(std::optional<AccelKind> requested, bool* fell_back = nullptr);
// Throws InputError when `kind` is Embree and this build lacks it.
std::unique_ptr<Accelerator> make_accelerator(AccelKind kind, std::vector<Primitive> prims);

}  // namespace caustica
