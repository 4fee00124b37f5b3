// The BSDF interface: evaluated and sampled in the local shading frame (z = surface normal),
// with lobe flags (diffuse, glossy, specular; reflection, transmission) as pbrt-v4's BxDFFlags.
// One plugin per file pair in core/bsdf/, each listed once in core/bsdf/registry.cpp. What a
// surface emits belongs to its area light, not to its BSDF.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include "core/math.h"
#include "core/textures/texture.h"

namespace caustica {

enum BsdfFlags : uint32_t {
  kBsdfReflection = 1u << 0,
  kBsdfTransmission = 1u << 1,
  kBsdfDiffuse = 1u << 2,
  kBsdfGlossy = 1u << 3,
  kBsdfSpecular = 1u << 4,  // a delta lobe: eval and pdf are zero, only sample reaches it
  // A delta transmission that keeps the direction (thindielectric's): Mitsuba's null lobe. In
  // scenes with media, as Mitsuba's volpath: no vertex where max_depth counts them, and shadow
  // rays pass it with its weight (null_transmission).
  kBsdfNull = 1u << 5,
};

// What a BSDF may vary with over a surface: where its textures are looked up (the texture
// coordinates, Mitsuba's convention: (0, 0) at the image's top-left; a mesh's attributes), and
// how the surface moves with (u, v) (for bump mapping): dp/du and dp/dv in the local shading
// frame, world units per unit of u and v (zero where the surface has no texture coordinates).
struct ShadingPoint : TexturePoint {
  Vec3 dpdu{0.0f}, dpdv{0.0f};
  // A tilted BSDF's (bump or normal map's) frame here, kept by the first of its calls at this
  // point (TiltedFrameBsdf::frame_at) for the others: a bump map's frame takes several texture
  // lookups, and a vertex evaluates, samples and takes the density of its BSDF. Cleared
  // whenever the point is filled (Scene's surface data).
  mutable const void* tilted_by = nullptr;
  mutable Frame tilted;
};

struct BsdfSample {
  Vec3 wi;        // local frame
  Color weight;   // f * |cos theta_i| / pdf (for a delta lobe: its reflectance or transmittance)
  float pdf = 0;  // solid-angle density; 0 for a delta lobe
  bool delta = false;
  uint32_t lobe = 0;  // the flags of the lobe that was sampled
  bool null() const { return (lobe & kBsdfNull) != 0; }
};

class Bsdf {
 public:
  virtual ~Bsdf() = default;
  // f(wo, wi) for local directions, non-delta lobes only. Every call takes the shading point
  // last (textures); untextured BSDFs ignore it, and tests may leave it out.
  virtual Color eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const = 0;
  // Solid-angle density with which sample() picks wi, non-delta lobes only.
  virtual float pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) const = 0;
  // u: two uniform numbers for the direction, u_lobe: one to choose a lobe.
  virtual bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const = 0;
  // The union of the lobes' flags.
  virtual uint32_t flags() const = 0;
  // The microfacet alpha of the narrowest glossy lobe (0 without one); photon mapping compares
  // it with its glossy threshold to decide whether photons are stored on the surface.
  virtual float glossy_roughness() const { return 0.0f; }
  // Hemispherical reflectance at normal incidence, or an estimate of it; exact for diffuse.
  virtual Color albedo(const ShadingPoint& sp = {}) const = 0;
  // The delta lobes seen from wo, each with its weight (at most two: reflection and
  // refraction), or for a purely glossy BSDF its smooth limit. Lets an integrator follow both
  // branches instead of choosing one at random (and Whitted treat glossy as specular).
  virtual int specular_lobes(const Vec3& /*wo*/, BsdfSample* /*out*/, const ShadingPoint& = {}) const { return 0; }
  // What a null lobe (kBsdfNull) lets through seen from wo: in scenes with media, shadow rays
  // pass such a surface with this weight (Mitsuba's eval_null_transmission); 0 without one.
  virtual Color null_transmission(const Vec3& /*wo*/, const ShadingPoint& = {}) const { return Color(0.0f); }
  // The probability that a ray stops at the surface (Mitsuba's `mask`); 1 for opaque ones.
  virtual float opacity(const ShadingPoint& = {}) const { return 1.0f; }
  virtual bool has_mask() const { return false; }
  // For a BSDF that refracts: the index on the far side of the boundary over the index on wo's
  // side (eta_t / eta_i seen from the viewer), 1 for one that does not. eval() and sample()
  // weights are the adjoint's, right for photons (flux); radiance crossing the boundary towards
  // wo is scaled by 1 / eta^2 more (radiance_scale below; Veach 1997, ch. 5).
  virtual float refraction_eta(const Vec3& /*wo*/, const ShadingPoint& = {}) const { return 1.0f; }

  bool has(uint32_t flag) const { return (flags() & flag) != 0; }
  // Only delta lobes: no direction can be evaluated, only sampled.
  bool is_specular() const { return (flags() & (kBsdfDiffuse | kBsdfGlossy)) == 0; }
  // A single diffuse reflection lobe: f = albedo / pi everywhere (not so under a normal map).
  virtual bool is_lambertian() const { return flags() == (kBsdfDiffuse | kBsdfReflection); }
  // Reflects about albedo / pi times the irradiance: exactly when Lambertian; for a diffuse
  // lobe in a tilted frame (bump and normal maps) the irradiance about the tilted normal, which
  // a final gather's second bounce may read from the irradiance about the surface's.
  virtual bool diffuse_in_some_frame() const { return is_lambertian(); }
};

// What turns a BSDF weight for (wo, wi) into the weight of radiance arriving along wi and
// leaving along wo: 1 / eta^2 for a refraction (wi on the other side), 1 otherwise. Eye paths
// (next-event estimation, sampled and split lobes) take it; photons do not.
inline float radiance_scale(const Bsdf& m, const Vec3& wo, const Vec3& wi, const ShadingPoint& sp = {}) {
  if (wo.z * wi.z >= 0.0f) return 1.0f;
  const float eta = m.refraction_eta(wo, sp);
  return 1.0f / (eta * eta);
}
// A sample's weight for radiance (an eye path's): its weight times radiance_scale.
inline Color radiance_weight(const Bsdf& m, const Vec3& wo, const BsdfSample& s, const ShadingPoint& sp = {}) {
  return s.weight * radiance_scale(m, wo, s.wi, sp);
}

// The glossy roughness of a BSDF made of two (twosided, blendbsdf): the narrower glossy lobe's.
float narrowest_glossy(const Bsdf& a, const Bsdf& b);

// Completes a sample of a non-delta lobe once its direction wi (upper hemisphere, wo's side
// mirrored up) is chosen: the density and weight come from the BSDF's own pdf() and eval(), so
// mixtures of lobes stay consistent; `lobe` is recorded, and the direction mirrored back down
// when wo was `below`. False when wi is below or has no density.
bool complete_sample(const Bsdf& m, const Vec3& wo, const Vec3& wi, uint32_t lobe, bool below,
                     const ShadingPoint& sp, BsdfSample& s);

// A BSDF with delta lobes only (mirrors, smooth glass): nothing to evaluate; sample() picks
// one of specular_lobes() in proportion to its weight (at most two, whose weights sum to 1 or
// less), and the sample carries the rest of the weight.
class SpecularBsdf : public Bsdf {
 public:
  Color eval(const Vec3&, const Vec3&, const ShadingPoint& = {}) const final { return Color(0.0f); }
  float pdf(const Vec3&, const Vec3&, const ShadingPoint& = {}) const final { return 0.0f; }
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp = {}) const final;
};

inline Vec3 reflect_local(const Vec3& wo) { return Vec3(-wo.x, -wo.y, wo.z); }
// Mirror reflection of wo about the unit vector m.
inline Vec3 reflect(const Vec3& wo, const Vec3& m) { return 2.0f * glm::dot(wo, m) * m - wo; }

}  // namespace caustica
