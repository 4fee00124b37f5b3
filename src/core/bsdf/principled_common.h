// What Mitsuba 3's `principled` and `principledthin` share: their Fresnel and Schlick terms,
// roughness to microfacet alphas, the Disney diffuse with retro-reflection and flatness, the
// sheen tint, and their parameters that may each be a number or a texture.
//
// Directions here are named as in Mitsuba: `wi` towards the viewer (our BSDFs' wo), `wo`
// towards the light (our wi); every value below is Mitsuba's f |cos wo|.
#pragma once
#include <string>
#include "core/bsdf/microfacet.h"
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica::principled {

// A parameter that is a number or a texture (a colour texture's luminance); `has` is Mitsuba's
// flag: given, and not the number 0 (a lobe whose flag is off is skipped).
struct Param {
  ColorParam value;
  bool has = false;
  float at(const TexturePoint& uv) const { return value.texture ? luminance(value.texture->eval(uv)) : value.value.x; }
};
// key as a number or a texture, default `fallback`; values outside [lo, hi] are refused
// where they are numbers (texture values are used as they come).
Param read(const Params& p, const std::string& key, float fallback, float lo, float hi);

// The parameters both plugins take.
struct Shared {
  ColorParam base_color{Color(0.5f)};
  Param roughness, anisotropic, spec_trans, spec_tint, sheen, sheen_tint, flatness;
  static Shared read(const Params& p);
  // The GGX lobe's narrower alpha for a constant roughness; 0 (traced through by photons)
  // where a texture may make it narrow.
  float glossy_roughness() const;
};

inline float schlick_weight(float c) {
  const float x = std::clamp(1.0f - c, 0.0f, 1.0f);
  const float x2 = x * x;
  return x2 * x2 * x;
}
inline float r0_of(float eta) {
  const float r = (eta - 1.0f) / (eta + 1.0f);
  return r * r;
}
inline Vec3 mulsign(const Vec3& v, float s) { return std::signbit(s) ? -v : v; }

// Dielectric Fresnel at the signed cosine c for relative index eta (the branch by the sign of
// c), with the transmitted cosine (of the opposite sign) and the indices on each side.
struct Fresnel {
  float F = 0, cos_t = 0, eta_it = 1, eta_ti = 1;
};
Fresnel fresnel(float c, float eta);
// Schlick's approximation from R0, at the cosine on the denser side (Mitsuba's calc_schlick).
Color schlick(const Color& r0, float c, float eta);
// Refraction of wi through the microfacet m with Fresnel's transmitted cosine.
inline Vec3 refract(const Vec3& wi, const Vec3& m, const Fresnel& f) {
  return m * (glm::dot(wi, m) * f.eta_ti + f.cos_t) - f.eta_ti * wi;
}
// Whether the microfacet m (turned to wi's side of the surface) reflects or refracts wi into wo.
inline bool compatible(const Vec3& m, const Vec3& wi, const Vec3& wo, float cos_i, bool reflection) {
  const Vec3 mt = mulsign(m, cos_i);
  return glm::dot(wi, mt) > 0.0f && (reflection ? glm::dot(wo, mt) > 0.0f : glm::dot(wo, mt) < 0.0f);
}

// GGX alphas from roughness and anisotropy (alpha = roughness^2, stretched by
// sqrt(1 - 0.9 anisotropic)), at least 0.001.
MicrofacetDistribution ggx(float roughness, float anisotropic, bool has_anisotropic);
// Smith's G1 for the GGX lobe, zero where w sees the back of m.
float smith_g1(const MicrofacetDistribution& d, const Vec3& w, const Vec3& m);
// Density of the visible normal m seen from wi (wi.z > 0).
float visible_pdf(const MicrofacetDistribution& d, const Vec3& wi, const Vec3& m);

// base / luminance(base), white for black.
Color tint_of(const Color& base);
// The sheen's colour: white blended towards the tint by sheen_tint (white when not given).
inline Color sheen_colour(const Param& sheen_tint, float amount, const Color& tint) {
  return sheen_tint.has ? Color(1.0f - amount) + amount * tint : Color(1.0f);
}

// The Disney diffuse factor with retro-reflection, blended towards the fake subsurface term by
// flatness: cos_d = h . wo, Fo and Fi the Schlick weights of |cos wo| and |cos wi|.
float diffuse_factor(float roughness, float cos_d, float cos_o, float cos_i, float flatness, bool has_flatness);

}  // namespace caustica::principled
