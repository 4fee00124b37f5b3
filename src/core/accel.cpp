// Choosing the ray-casting backend.
#include "core/accel.h"
#include "core/bvh.h"
#include "core/embree_accel.h"
#include "core/error.h"

namespace caustica {

bool parse_accel(const std::string& name, AccelKind& kind) {
  if (name == "bvh") kind = AccelKind::Bvh;
  else if (name == "embree") kind = AccelKind::Embree;
  else return false;
  return true;
}

bool embree_available() {
#ifdef CAUSTICA_EMBREE
  return true;
#else
  return false;
#endif
}

AccelKind default_accel() { return embree_available() ? AccelKind::Embree : AccelKind::Bvh; }

AccelKind choose_accel(std::optional<AccelKind> requested, bool* fell_back) {
  if (fell_back) *fell_back = false;
  if (!requested) return default_accel();
  if (*requested == AccelKind::Embree && !embree_available()) {
    if (fell_back) *fell_back = true;
    return AccelKind::Bvh;
  }
  return *requested;
}

std::unique_ptr<Accelerator> make_accelerator(AccelKind kind, std::vector<Primitive> prims) {
  if (kind == AccelKind::Embree) {
#ifdef CAUSTICA_EMBREE
    return std::make_unique<EmbreeAccel>(std::move(prims));
#else
    throw InputError("accel \"embree\": this build of Caustica has no Embree (install libembree-dev and rebuild)");
#endif
  }
  auto bvh = std::make_unique<Bvh>();
  bvh->build(std::move(prims));
  return bvh;
}

}  // namespace caustica
