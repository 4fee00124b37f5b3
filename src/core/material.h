// Materials: BSDFs evaluated and sampled in the local shading frame (z = surface normal),
// flagged diffuse (photons are stored there) or delta (mirror, glass), plus emitted radiance.
#pragma once
#include <memory>
#include <string>
#include "core/math.h"

namespace caustica {

struct BsdfSample {
  Vec3 wi;       // local frame
  Color weight;  // f * |cos theta_i| / pdf
  float pdf = 0; // solid-angle density; 0 for a delta lobe
  bool delta = false;
};

class Material {
 public:
  virtual ~Material() = default;
  // f(wo, wi) for local directions; zero for delta lobes.
  virtual Color eval(const Vec3& wo, const Vec3& wi) const = 0;
  virtual float pdf(const Vec3& wo, const Vec3& wi) const = 0;
  // u: two uniform numbers for the direction, u_lobe: one to choose a lobe.
  virtual bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s) const = 0;
  // True for Lambertian surfaces; photons are stored and final gathering happens there.
  virtual bool is_diffuse() const = 0;
  bool is_delta() const { return !is_diffuse(); }
  // Hemispherical reflectance (survival probability for photon Russian roulette).
  virtual Color albedo() const = 0;

  Color emission{0.0f};  // radiance leaving the front side (along the normal)
  bool is_emissive() const { return !is_black(emission); }
  // Radiance emitted towards local direction wo.
  Color emitted(const Vec3& wo_local) const { return wo_local.z > 0 ? emission : Color(0.0f); }
};

class Lambertian final : public Material {
 public:
  explicit Lambertian(const Color& albedo) : albedo_(albedo) {}
  Color eval(const Vec3& wo, const Vec3& wi) const override;  // rho / pi, two-sided
  float pdf(const Vec3& wo, const Vec3& wi) const override;
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s) const override;
  bool is_diffuse() const override { return true; }
  Color albedo() const override { return albedo_; }

 private:
  Color albedo_;
};

class Mirror final : public Material {
 public:
  explicit Mirror(const Color& reflectance) : reflectance_(reflectance) {}
  Color eval(const Vec3&, const Vec3&) const override { return Color(0.0f); }
  float pdf(const Vec3&, const Vec3&) const override { return 0.0f; }
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s) const override;
  bool is_diffuse() const override { return false; }
  Color albedo() const override { return reflectance_; }

 private:
  Color reflectance_;
};

enum class FresnelModel { Exact, Schlick };

// Unpolarised Fresnel reflectance of a dielectric boundary. cos_i > 0 is measured on the
// incident side; eta = n_transmitted / n_incident. Returns 1 under total internal reflection.
float fresnel_dielectric(float cos_i, float eta);
float fresnel_schlick(float cos_i, float eta);

// Smooth glass: Fresnel chooses reflection or refraction (Snell's law).
class Glass final : public Material {
 public:
  Glass(float ior, FresnelModel model) : ior_(ior), model_(model) {}
  Color eval(const Vec3&, const Vec3&) const override { return Color(0.0f); }
  float pdf(const Vec3&, const Vec3&) const override { return 0.0f; }
  bool sample(const Vec3& wo, const Vec2& u, float u_lobe, BsdfSample& s) const override;
  bool is_diffuse() const override { return false; }
  Color albedo() const override { return Color(1.0f); }
  // Reflectance for local direction wo (either side of the boundary).
  float reflectance(const Vec3& wo) const;
  // Refracted local direction for wo; false under total internal reflection.
  bool refract(const Vec3& wo, Vec3& wt) const;
  float ior() const { return ior_; }

 private:
  float ior_;
  FresnelModel model_;
};

inline Vec3 reflect_local(const Vec3& wo) { return Vec3(-wo.x, -wo.y, wo.z); }

}  // namespace caustica
