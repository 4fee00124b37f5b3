// Shared terms of the principled BSDFs.
#include "core/bsdf/principled_common.h"
#include <cmath>
#include <sstream>

namespace caustica::principled {

Param read(const Params& p, const std::string& key, float fallback, float lo, float hi) {
  Param out;
  out.value = p.texture(key, Color(fallback));
  if (!out.value.texture) {
    const Color& c = out.value.value;
    if (c.y != c.x || c.z != c.x) p.fail(key, key + " must be one number (or a texture)");
    if (!(c.x >= lo && c.x <= hi)) {
      std::ostringstream m;
      m << key << " must be from " << lo << " to " << hi;
      p.fail(key, m.str());
    }
  }
  out.has = p.has(key) && (out.value.texture || out.value.value.x != 0.0f);
  return out;
}

Shared Shared::read(const Params& p) {
  Shared s;
  s.base_color = p.texture("base_color", Color(0.5f));
  s.roughness = principled::read(p, "roughness", 0.5f, 0.0f, 1.0f);
  s.anisotropic = principled::read(p, "anisotropic", 0.0f, 0.0f, 1.0f);
  s.spec_trans = principled::read(p, "spec_trans", 0.0f, 0.0f, 1.0f);
  s.spec_tint = principled::read(p, "spec_tint", 0.0f, 0.0f, 1.0f);
  s.sheen = principled::read(p, "sheen", 0.0f, 0.0f, 1.0f);
  s.sheen_tint = principled::read(p, "sheen_tint", 0.0f, 0.0f, 1.0f);
  s.flatness = principled::read(p, "flatness", 0.0f, 0.0f, 1.0f);
  return s;
}

float Shared::glossy_roughness() const {
  if (roughness.value.texture || anisotropic.value.texture) return 0.0f;
  const MicrofacetDistribution d = ggx(roughness.value.value.x, anisotropic.value.value.x, anisotropic.has);
  return std::min(d.alpha_u(), d.alpha_v());
}

Fresnel fresnel(float c, float eta) {
  Fresnel f;
  const bool outside = c >= 0.0f;
  f.eta_it = outside ? eta : 1.0f / eta;
  f.eta_ti = outside ? 1.0f / eta : eta;
  const float ct2 = 1.0f - (1.0f - c * c) * f.eta_ti * f.eta_ti;
  const float ct = std::sqrt(std::max(ct2, 0.0f));
  const float ac = std::abs(c);
  const float as = (ac - f.eta_it * ct) / (ac + f.eta_it * ct);
  const float ap = (ct - f.eta_it * ac) / (ct + f.eta_it * ac);
  f.F = 0.5f * (as * as + ap * ap);
  if (eta == 1.0f) f.F = 0.0f;
  else if (ac == 0.0f) f.F = 1.0f;
  f.cos_t = outside ? -ct : ct;
  return f;
}

Color schlick(const Color& r0, float c, float eta) {
  const bool outside = c >= 0.0f;
  const float eta_it = outside ? eta : 1.0f / eta, eta_ti = outside ? 1.0f / eta : eta;
  const float ct = std::sqrt(std::max(0.0f, 1.0f - (1.0f - c * c) * eta_ti * eta_ti));
  const float w = schlick_weight(eta_it > 1.0f ? std::abs(c) : ct);
  return r0 + (Color(1.0f) - r0) * w;
}

MicrofacetDistribution ggx(float roughness, float anisotropic, bool has_anisotropic) {
  const float r2 = roughness * roughness;
  if (!has_anisotropic) {
    const float a = std::max(0.001f, r2);
    return MicrofacetDistribution(MicrofacetType::GGX, a, a);
  }
  const float aspect = std::sqrt(std::max(0.0f, 1.0f - 0.9f * anisotropic));
  return MicrofacetDistribution(MicrofacetType::GGX, std::max(0.001f, r2 / aspect), std::max(0.001f, r2 * aspect));
}

float smith_g1(const MicrofacetDistribution& d, const Vec3& w, const Vec3& m) {
  if (glm::dot(w, m) * w.z <= 0.0f) return 0.0f;
  return d.G1(w);
}

float visible_pdf(const MicrofacetDistribution& d, const Vec3& wi, const Vec3& m) {
  if (!(wi.z > 0.0f)) return 0.0f;
  return d.D(m) * smith_g1(d, wi, m) * std::abs(glm::dot(wi, m)) / wi.z;
}

Color tint_of(const Color& base) {
  const float l = luminance(base);
  return l > 0.0f ? base / l : Color(1.0f);
}

float diffuse_factor(float r, float cos_d, float cos_o, float cos_i, float flatness, bool has_flatness) {
  const float fo = schlick_weight(cos_o), fi = schlick_weight(cos_i);
  const float f_diff = (1.0f - 0.5f * fi) * (1.0f - 0.5f * fo);
  const float rr = 2.0f * r * cos_d * cos_d;
  const float f_retro = rr * (fo + fi + fo * fi * (rr - 1.0f));
  if (!has_flatness) return f_diff + f_retro;
  const float fss90 = 0.5f * rr;
  const float fss = (1.0f + (fss90 - 1.0f) * fo) * (1.0f + (fss90 - 1.0f) * fi);
  const float f_ss = 1.25f * (fss * (1.0f / (cos_o + cos_i) - 0.5f) + 0.5f);
  return (1.0f - flatness) * (f_diff + f_retro) + flatness * f_ss;
}

}  // namespace caustica::principled
