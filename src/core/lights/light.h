// The light (emitter) interface: sampled for shadow rays (next-event estimation) and for photon
// emission. One plugin per file pair in core/lights/, each listed once in
// core/lights/registry.cpp; area lights are made by the scene reader from emissive objects.
#pragma once
#include <memory>
#include <vector>
#include "core/light_bounds.h"
#include "core/sampling.h"
#include "core/shape.h"

namespace caustica {

// A point on a light seen from a shading point.
struct LightSample {
  Vec3 p;         // point on the light
  Vec3 n;         // its normal (zero for a point light)
  Vec3 wi;        // unit direction from the shading point to p
  float dist = 0; // distance to p
  Color weight;   // incident radiance / solid-angle pdf (Le cos_l / (d^2 pdf_A), or I / d^2)
  float pdf = 0;  // solid-angle density of wi (0 for a delta light), not counting the light's pmf
};

// A point from which a light's photons leave: its normal (zero for a point light), the area
// density with which it was chosen (1 for a point light), and its texture coordinates.
struct LightPoint {
  Vec3 p{0.0f};
  Vec3 n{0.0f};
  float pdf = 0;
  TexturePoint at;  // where a textured emission is looked up
};

// A photon leaving a light.
struct EmittedPhoton {
  Vec3 origin;
  Vec3 normal;  // zero for a point light
  Vec3 dir;
  Color flux;  // the light's power when one photon is emitted: Le cos / (pdf_A pdf_w)
};

class Light {
 public:
  virtual ~Light() = default;
  virtual bool sample_li(const Vec3& x, const Vec2& u, LightSample& s) const = 0;
  virtual EmittedPhoton sample_emission(const Vec2& u_pos, const Vec2& u_dir) const = 0;
  // A point on the light (normal zero and pdf 1 for a point light; else area density).
  virtual LightPoint sample_origin(const Vec2& u) const = 0;
  // Radiant intensity per unit area (Le cos) or per light (I) leaving `at` along dir.
  virtual Color emitted_towards(const LightPoint& at, const Vec3& dir) const = 0;
  virtual Color power() const = 0;
  // The radiance that an emitting surface sends out of its front side at a point (its texture
  // coordinates and mesh attributes: area lights; zero else).
  virtual Color surface_radiance(const TexturePoint& /*at*/ = {}) const { return Color(0.0f); }
  virtual bool is_delta() const = 0;
  virtual Bounds bounds() const = 0;
  // For the spatial light sampler (finite lights): bounds() emitting in every direction with
  // the power times the sampling weight, unless a light knows a tighter cone.
  virtual LightBounds light_bounds() const;
  // Solid-angle density with which sample_li from x picks the point y (normal ny) on the light;
  // 0 for delta lights. For multiple importance sampling of BSDF-sampled hits.
  virtual float pdf_li(const Vec3& /*x*/, const Vec3& /*y*/, const Vec3& /*ny*/) const { return 0.0f; }

  // Lights at infinity (directional, environment): they learn the scene's bounding sphere
  // before power() is asked, emit photons from a disc outside it, and are seen by rays that
  // escape the scene.
  virtual bool is_infinite() const { return false; }
  virtual void set_scene_sphere(const Vec3& /*centre*/, float /*radius*/) {}
  // Radiance arriving along a ray that escapes in direction dir, and the solid-angle density
  // with which sample_li picks dir (for MIS); zero for finite and delta lights.
  virtual Color escaped(const Vec3& /*dir*/) const { return Color(0.0f); }
  virtual float pdf_escaped(const Vec3& /*dir*/) const { return 0.0f; }
  // An infinite light's direction of travel for photons and the radiance (irradiance for a
  // delta direction) divided by the direction's density.
  virtual bool sample_travel(const Vec2& /*u*/, Vec3& /*dir*/, Color& /*value*/) const { return false; }

  // Mitsuba's sampling_weight: lights are chosen (for shadow rays and photons) in proportion to
  // their power times this weight; estimates divide by the probability, so the image's
  // expectation does not change, only where the samples go.
  float sampling_weight() const { return sampling_weight_; }
  // What lights are chosen in proportion to (by power): average power times the weight.
  float sampling_power() const { return std::max(0.0f, average(power())) * sampling_weight_; }
  void set_sampling_weight(float w) { sampling_weight_ = w; }

 private:
  float sampling_weight_ = 1.0f;
};

// Lights at infinity keep the scene's bounding sphere: their photons start outside it.
class InfiniteLight : public Light {
 public:
  Bounds bounds() const final { return Bounds{}; }
  bool is_infinite() const final { return true; }
  void set_scene_sphere(const Vec3& centre, float radius) final {
    centre_ = centre;
    radius_ = std::max(radius, 1e-6f);
  }

 protected:
  Vec3 centre_{0.0f};
  float radius_ = 1.0f;
};

// A point uniformly on the disc of radius r centred at c perpendicular to the unit vector d.
Vec3 point_on_disc(const Vec3& c, const Vec3& d, float r, const Vec2& u);

}  // namespace caustica
