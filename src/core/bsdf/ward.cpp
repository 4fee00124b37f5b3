// The Ward BRDF.
#include "core/bsdf/ward.h"
#include "core/bsdf/bsdf_params.h"
#include "core/bsdf/diffuse.h"
#include "core/sampling.h"

namespace caustica {

Vec2 Ward::alphas(const ShadingPoint& sp) const {
  return Vec2(std::max(1e-4f, average(alpha_u_.at(sp))), std::max(1e-4f, average(alpha_v_.at(sp))));
}

Color Ward::eval(const Vec3& wo_in, const Vec3& wi_in, const ShadingPoint& sp) const {
  if (wo_in.z * wi_in.z <= 0.0f) return Color(0.0f);
  const Vec3 wo = wo_in.z < 0 ? flip_z(wo_in) : wo_in, wi = wo_in.z < 0 ? flip_z(wi_in) : wi_in;
  const Vec2 a = alphas(sp);
  const Vec3 h = wo + wi;  // not normalised: its length drops out of the exponent
  const float e = std::exp(-((h.x / a.x) * (h.x / a.x) + (h.y / a.y) * (h.y / a.y)) / (h.z * h.z));
  float norm = 0.0f;
  switch (variant_) {
    case WardVariant::Ward: norm = 1.0f / (4.0f * kPi * a.x * a.y * std::sqrt(wo.z * wi.z)); break;
    case WardVariant::WardDuer: norm = 1.0f / (4.0f * kPi * a.x * a.y * wo.z * wi.z); break;
    case WardVariant::Balanced: {
      const float hz2 = h.z * h.z;
      norm = glm::dot(h, h) / (kPi * a.x * a.y * hz2 * hz2);
      break;
    }
  }
  float fs = norm * e;
  if (!(fs > 1e-10f) || !std::isfinite(fs)) fs = 0.0f;
  return specular_.at(sp) * fs + diffuse_.at(sp) * kInvPi;
}

float Ward::pdf(const Vec3& wo_in, const Vec3& wi_in, const ShadingPoint& sp) const {
  if (wo_in.z * wi_in.z <= 0.0f) return 0.0f;
  const Vec3 wo = wo_in.z < 0 ? flip_z(wo_in) : wo_in, wi = wo_in.z < 0 ? flip_z(wi_in) : wi_in;
  const Vec2 a = alphas(sp);
  const Vec3 h = glm::normalize(wo + wi);
  // The half vector's density exp(-tan^2 (cos^2 phi / au^2 + sin^2 phi / av^2)) / (pi au av
  // cos^3), times the reflection's Jacobian 1 / (4 wo.h).
  const float p_spec = std::exp(-((h.x / a.x) * (h.x / a.x) + (h.y / a.y) * (h.y / a.y)) / (h.z * h.z)) /
                       (4.0f * kPi * a.x * a.y * glm::dot(h, wo) * h.z * h.z * h.z);
  const float p = p_specular_ * (std::isfinite(p_spec) ? p_spec : 0.0f) + (1.0f - p_specular_) * wi.z * kInvPi;
  return p > 0.0f ? p : 0.0f;
}

bool Ward::sample(const Vec3& wo_in, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp) const {
  if (wo_in.z == 0.0f) return false;
  const bool below = wo_in.z < 0.0f;
  const Vec3 wo = below ? flip_z(wo_in) : wo_in;
  Vec3 wi;
  if (u_lobe < p_specular_) {
    const Vec2 a = alphas(sp);
    // Walter 2005: the half vector's azimuth, stretched by av / au, in the quadrant of 2 pi u.y.
    float phi = std::atan(a.y / a.x * std::tan(2.0f * kPi * u.y));
    if (u.y > 0.5f) phi += kPi;
    const float c = std::cos(phi), sn = std::sin(phi);
    const float denom = c * c / (a.x * a.x) + sn * sn / (a.y * a.y);
    const float theta = std::atan(std::sqrt(-std::log(std::max(u.x, 1e-30f)) / denom));
    const Vec3 h(std::sin(theta) * c, std::sin(theta) * sn, std::cos(theta));
    wi = reflect(wo, h);
    s.lobe = kBsdfGlossy | kBsdfReflection;
  } else {
    wi = sample_cosine_hemisphere(u);
    s.lobe = kBsdfDiffuse | kBsdfReflection;
  }
  if (!(wi.z > 0.0f)) return false;
  s.pdf = pdf(wo, wi, sp);
  if (!(s.pdf > 0.0f)) return false;
  s.weight = eval(wo, wi, sp) * (wi.z / s.pdf);
  s.wi = below ? flip_z(wi) : wi;
  s.delta = false;
  return is_finite(s.weight);
}

uint32_t Ward::flags() const {
  uint32_t f = kBsdfReflection;
  if (!specular_.is_black()) f |= kBsdfGlossy;
  if (!diffuse_.is_black()) f |= kBsdfDiffuse;
  return f;
}

float Ward::glossy_roughness() const {
  if (alpha_u_.texture || alpha_v_.texture) return 0.0f;
  return std::min(average(alpha_u_.value), average(alpha_v_.value));
}

std::unique_ptr<Bsdf> Ward::create(const Params& p) {
  const std::string v = p.string("variant", "balanced");
  WardVariant variant = WardVariant::Balanced;
  if (v == "ward") variant = WardVariant::Ward;
  else if (v == "ward-duer") variant = WardVariant::WardDuer;
  else if (v != "balanced") p.fail("variant", "unknown Ward variant \"" + v + "\" (known: ward, ward-duer, balanced)");
  const float alpha = float(p.number_in("alpha", 0.1, 1e-4, 10.0));
  ColorParam au = p.texture("alpha_u", Color(alpha)), av = p.texture("alpha_v", Color(alpha));
  for (const char* key : {"alpha_u", "alpha_v"}) {
    const ColorParam& c = key[6] == 'u' ? au : av;
    if (!c.texture && !(c.value.x > 0.0f)) p.fail(key, std::string(key) + " must be positive");
  }
  ColorParam specular = p.texture("specular_reflectance", Color(0.2f)), diffuse = p.texture("diffuse_reflectance", Color(0.5f));
  // Mitsuba's energy check, for constant reflectances: if a channel's sum exceeds 1, both are
  // scaled by 0.99 / (the largest sum).
  if (p.boolean("ensure_energy_conservation", true) && !specular.texture && !diffuse.texture) {
    const Color sum = specular.value + diffuse.value;
    const float m = std::max({sum.x, sum.y, sum.z});
    if (m > 1.0f) {
      p.warn("specular_reflectance", "specular and diffuse reflectance add up to more than 1: both scaled by 0.99 / " + std::to_string(m));
      specular.value *= 0.99f / m;
      diffuse.value *= 0.99f / m;
    }
  }
  // The specular lobe's share of samples: its reflectance's luminance over both (a texture
  // counts as its value at the centre). With a texture, each lobe keeps at least a tenth of the
  // samples: where the texture is not what its centre says (a mesh attribute reads black
  // there), a lobe must not go unsampled.
  const float s = luminance(specular.at(Vec2(0.5f))), d = luminance(diffuse.at(Vec2(0.5f)));
  float p_spec = s + d > 0.0f ? s / (s + d) : 0.5f;
  if (specular.texture || diffuse.texture) p_spec = std::clamp(p_spec, 0.1f, 0.9f);
  return std::make_unique<Ward>(variant, au, av, specular, diffuse, p_spec);
}

}  // namespace caustica
