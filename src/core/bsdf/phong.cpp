// Normalised modified Phong: the diffuse lobe sampled by cosine, the specular one by
// cos^n around the mirror direction, chosen in proportion to their reflectances.
#include "core/bsdf/phong.h"
#include "core/bsdf/diffuse.h"
#include "core/sampling.h"

namespace caustica {

Phong::Phong(const ColorParam& diffuse, const ColorParam& specular, float exponent)
    : kd_(diffuse), ks_(specular), exponent_(exponent) {}

uint32_t Phong::flags() const {
  uint32_t f = kBsdfReflection;
  if (!kd_.is_black()) f |= kBsdfDiffuse;
  if (!ks_.is_black()) f |= kBsdfGlossy;
  return f;
}

float Phong::specular_probability(const ShadingPoint& sp) const {
  const float d = average(kd_.at(sp)), s = average(ks_.at(sp));
  return d + s > 0.0f ? s / (d + s) : 0.0f;
}

Color Phong::eval(const Vec3& wo_in, const Vec3& wi_in, const ShadingPoint& sp) const {
  if (wo_in.z * wi_in.z <= 0.0f) return Color(0.0f);
  const Vec3 wo = wo_in.z < 0 ? flip_z(wo_in) : wo_in, wi = wo_in.z < 0 ? flip_z(wi_in) : wi_in;
  const float cos_a = glm::dot(reflect_local(wo), wi);
  Color f = kd_.at(sp) * kInvPi;
  if (cos_a > 0.0f) f += ks_.at(sp) * ((exponent_ + 2.0f) / (2.0f * kPi) * std::pow(cos_a, exponent_));
  return f;
}

float Phong::pdf(const Vec3& wo_in, const Vec3& wi_in, const ShadingPoint& sp) const {
  if (wo_in.z * wi_in.z <= 0.0f) return 0.0f;
  const Vec3 wo = wo_in.z < 0 ? flip_z(wo_in) : wo_in, wi = wo_in.z < 0 ? flip_z(wi_in) : wi_in;
  const float cos_a = glm::dot(reflect_local(wo), wi);
  const float spec = cos_a > 0.0f ? (exponent_ + 1.0f) / (2.0f * kPi) * std::pow(cos_a, exponent_) : 0.0f;
  const float p = specular_probability(sp);
  return p * spec + (1.0f - p) * wi.z * kInvPi;
}

bool Phong::sample(const Vec3& wo_in, const Vec2& u, float u_lobe, BsdfSample& s, const ShadingPoint& sp) const {
  const float p = specular_probability(sp);
  if (wo_in.z == 0.0f || p + average(kd_.at(sp)) <= 0.0f) return false;
  const bool below = wo_in.z < 0;
  const Vec3 wo = below ? flip_z(wo_in) : wo_in;
  const bool glossy = u_lobe < p;
  Vec3 wi;
  if (glossy) {
    // cos^n-distributed around the mirror direction: cos a = u^(1 / (n + 1)).
    const float cos_a = std::pow(u.x, 1.0f / (exponent_ + 1.0f));
    const float sin_a = std::sqrt(std::max(0.0f, 1.0f - cos_a * cos_a));
    const float phi = 2.0f * kPi * u.y;
    wi = Frame(reflect_local(wo)).to_world(Vec3(sin_a * std::cos(phi), sin_a * std::sin(phi), cos_a));
  } else {
    wi = sample_cosine_hemisphere(u);
  }
  return complete_sample(*this, wo, wi, kBsdfReflection | (glossy ? kBsdfGlossy : kBsdfDiffuse), below, sp, s);
}

std::unique_ptr<Bsdf> Phong::create(const Params& p) {
  const ColorParam kd = p.texture("diffuse_reflectance", Color(0.5f));
  const ColorParam ks = p.texture("specular_reflectance", Color(0.2f));
  if (!kd.texture && !ks.texture && max_component(kd.value + ks.value) > 1.0f) {
    p.warn("", "diffuse_reflectance + specular_reflectance above 1 creates energy");
  }
  return std::make_unique<Phong>(kd, ks, float(p.number_in("exponent", 30.0, 0.0, 1e6)));
}

}  // namespace caustica
