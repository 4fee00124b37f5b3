// What every light shares.
#include "core/lights/light.h"

namespace caustica {

LightBounds Light::light_bounds() const {
  LightBounds b;
  b.bounds = bounds();
  b.normals = DirectionCone::everywhere();
  b.cos_theta_e = 0.0f;
  b.phi = sampling_power();
  return b;
}

Vec3 point_on_disc(const Vec3& c, const Vec3& d, float r, const Vec2& u) {
  const Vec2 q = sample_concentric_disk(u) * r;
  const Frame f(d);
  return c + q.x * f.s + q.y * f.t;
}

}  // namespace caustica
