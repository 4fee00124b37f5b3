// Phase functions: how a medium scatters light, as a density over the sphere of directions.
// Directions follow the BSDFs' convention: wo points back along the path (towards the camera
// or the previous vertex), wi onwards; the scattering angle is between the light's direction
// of travel (-wo) and wi. Energy-conserving and normalised: the value is also the density with
// which sample() picks wi, so a sample's weight is 1 (pbrt-v4's and Mitsuba 3's convention).
#pragma once
#include <memory>
#include "core/math.h"
#include "core/params.h"

namespace caustica {

class PhaseFunction {
 public:
  virtual ~PhaseFunction() = default;
  virtual float eval(const Vec3& wo, const Vec3& wi) const = 0;
  // Picks wi with density eval(wo, wi) from two uniform numbers; returns that density.
  virtual float sample(const Vec3& wo, const Vec2& u, Vec3& wi) const = 0;
  // The mean cosine of the scattering angle (g; 0 for isotropic).
  virtual float mean_cosine() const = 0;
};

class IsotropicPhase final : public PhaseFunction {
 public:
  float eval(const Vec3&, const Vec3&) const override { return 0.25f * kInvPi; }
  float sample(const Vec3& wo, const Vec2& u, Vec3& wi) const override;
  float mean_cosine() const override { return 0.0f; }
  static std::unique_ptr<PhaseFunction> create(const Params& p);
};

// Henyey and Greenstein (1941): g in (-1, 1), forward scattering for g > 0.
class HenyeyGreenstein final : public PhaseFunction {
 public:
  explicit HenyeyGreenstein(float g) : g_(g) {}
  float eval(const Vec3& wo, const Vec3& wi) const override;
  float sample(const Vec3& wo, const Vec2& u, Vec3& wi) const override;
  float mean_cosine() const override { return g_; }
  static std::unique_ptr<PhaseFunction> create(const Params& p);

 private:
  float g_;
};

// The density of HG with parameter g at cosine cos_theta of the scattering angle.
float henyey_greenstein(float cos_theta, float g);

}  // namespace caustica
