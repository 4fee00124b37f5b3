// Lambertian, mirror and glass BSDFs.
#include "core/material.h"
#include "core/sampling.h"

namespace caustica {

Color Lambertian::eval(const Vec3& wo, const Vec3& wi) const {
  return wo.z * wi.z > 0.0f ? albedo_ * kInvPi : Color(0.0f);
}

float Lambertian::pdf(const Vec3& wo, const Vec3& wi) const {
  return wo.z * wi.z > 0.0f ? std::abs(wi.z) * kInvPi : 0.0f;
}

bool Lambertian::sample(const Vec3& wo, const Vec2& u, float, BsdfSample& s) const {
  if (wo.z == 0.0f) return false;
  s.wi = sample_cosine_hemisphere(u);
  if (wo.z < 0.0f) s.wi.z = -s.wi.z;  // two-sided: scatter back to the side wo is on
  s.pdf = std::abs(s.wi.z) * kInvPi;
  if (s.pdf <= 0.0f) return false;
  s.weight = albedo_;  // (rho/pi) cos / (cos/pi)
  s.delta = false;
  return true;
}

bool Mirror::sample(const Vec3& wo, const Vec2&, float, BsdfSample& s) const {
  if (wo.z == 0.0f) return false;
  s.wi = reflect_local(wo);
  s.weight = reflectance_;
  s.pdf = 0.0f;
  s.delta = true;
  return true;
}

float fresnel_dielectric(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  const float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  const float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

float fresnel_schlick(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  const float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  // Schlick's approximation uses the angle on the optically thinner side.
  const float cos_x = eta >= 1.0f ? cos_i : std::sqrt(1.0f - sin2_t);
  const float r0 = ((eta - 1.0f) / (eta + 1.0f)) * ((eta - 1.0f) / (eta + 1.0f));
  const float m = 1.0f - cos_x;
  return r0 + (1.0f - r0) * m * m * m * m * m;
}

float Glass::reflectance(const Vec3& wo) const {
  const bool entering = wo.z > 0.0f;
  const float eta = entering ? ior_ : 1.0f / ior_;
  const float cos_i = std::abs(wo.z);
  return model_ == FresnelModel::Exact ? fresnel_dielectric(cos_i, eta) : fresnel_schlick(cos_i, eta);
}

bool Glass::refract(const Vec3& wo, Vec3& wt) const {
  const bool entering = wo.z > 0.0f;
  const float eta = entering ? ior_ : 1.0f / ior_;  // n_t / n_i
  const float cos_i = std::abs(wo.z);
  const float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return false;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  wt = Vec3(-wo.x / eta, -wo.y / eta, entering ? -cos_t : cos_t);
  return true;
}

bool Glass::sample(const Vec3& wo, const Vec2&, float u_lobe, BsdfSample& s) const {
  if (wo.z == 0.0f) return false;
  const float f = reflectance(wo);
  s.pdf = 0.0f;
  s.delta = true;
  s.weight = Color(1.0f);  // F / F or (1 - F) / (1 - F)
  Vec3 wt;
  if (u_lobe < f || !refract(wo, wt)) {
    s.wi = reflect_local(wo);
  } else {
    s.wi = wt;
  }
  return true;
}

}  // namespace caustica
