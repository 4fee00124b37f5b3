// What every light shares.
#include "core/lights/light.h"

namespace caustica {

Vec3 point_on_disc(const Vec3& c, const Vec3& d, float r, const Vec2& u) {
  const Vec2 q = sample_concentric_disk(u) * r;
  const Frame f(d);
  return c + q.x * f.s + q.y * f.t;
}

}  // namespace caustica
