// A homogeneous medium (Mitsuba's `homogeneous`): extinction sigma_t and single-scattering
// albedo everywhere the same, or sigma_a and sigma_s (pbrt's), times `scale`.
#pragma once
#include "core/media/medium.h"
#include "core/params.h"

namespace caustica {

class HomogeneousMedium final : public Medium {
 public:
  HomogeneousMedium(const Color& sigma_t, const Color& albedo, std::unique_ptr<PhaseFunction> phase);
  MediumEvent sample(const Ray& ray, float tmax, int channel, Sampler& sampler,
                     FlightRecord* record = nullptr) const override;
  Color transmittance(const Ray& ray, float tmax, Sampler& sampler) const override;
  const PhaseFunction& phase() const override { return *phase_; }
  bool homogeneous(Color& sigma_t, Color& sigma_s) const override {
    sigma_t = sigma_t_, sigma_s = sigma_s_;
    return true;
  }
  const Color& sigma_t() const { return sigma_t_; }
  const Color& sigma_s() const { return sigma_s_; }
  Color sigma_s(const Vec3&) const override { return sigma_s_; }
  static std::unique_ptr<Medium> create(const Params& p);

 private:
  Color sigma_t_, sigma_s_;
  std::unique_ptr<PhaseFunction> phase_;
};

// exp(-sigma_t * d) per channel (1 where sigma_t is 0, also for infinite d).
Color beer_lambert(const Color& sigma_t, float d);

}  // namespace caustica
