// Lambertian reflection.
#include "core/bsdf/diffuse.h"
#include "core/bsdf/bsdf_params.h"
#include "core/sampling.h"

namespace caustica {

Color Lambertian::eval(const Vec3& wo, const Vec3& wi, const ShadingPoint& sp) const {
  return wo.z * wi.z > 0.0f ? albedo_.at(sp) * kInvPi : Color(0.0f);
}

float Lambertian::pdf(const Vec3& wo, const Vec3& wi, const ShadingPoint&) const {
  return wo.z * wi.z > 0.0f ? std::abs(wi.z) * kInvPi : 0.0f;
}

bool Lambertian::sample(const Vec3& wo, const Vec2& u, float, BsdfSample& s, const ShadingPoint& sp) const {
  if (wo.z == 0.0f) return false;
  s.wi = sample_cosine_hemisphere(u);
  if (wo.z < 0.0f) s.wi.z = -s.wi.z;  // two-sided: scatter back to the side wo is on
  s.pdf = std::abs(s.wi.z) * kInvPi;
  if (s.pdf <= 0.0f) return false;
  s.weight = albedo_.at(sp);  // (rho/pi) cos / (cos/pi)
  s.delta = false;
  s.lobe = kBsdfDiffuse | kBsdfReflection;
  return true;
}

std::unique_ptr<Bsdf> Lambertian::create(const Params& p) {
  if (p.has("reflectance") && p.has("albedo")) p.fail("", "albedo is an alias of reflectance: give one");
  const char* key = p.has("albedo") ? "albedo" : "reflectance";
  const ColorParam rho = p.texture(key, Color(0.5f));
  check_albedo(p, key, rho);
  return std::make_unique<Lambertian>(rho);
}

}  // namespace caustica
