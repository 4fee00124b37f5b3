// A heterogeneous medium (Mitsuba's `heterogeneous`): extinction sigma_t and albedo given by
// volumes (a grid file, or a constant), times `scale`. Free flights by delta tracking and
// shadow rays' transmittance by ratio tracking (Novak et al. 2014), both against the grid's
// largest extinction as majorant, within the grid's box (the medium is empty outside it).
// sigma_t may be chromatic (three channels: tracked in the path's hero channel against the
// largest channel as majorant, with spectral MIS over the channels).
#pragma once
#include "core/media/medium.h"
#include "core/media/volume.h"

namespace caustica {

class HeterogeneousMedium final : public Medium {
 public:
  HeterogeneousMedium(std::unique_ptr<Volume> sigma_t, std::unique_ptr<Volume> albedo, float scale,
                      std::unique_ptr<PhaseFunction> phase);
  MediumEvent sample(const Ray& ray, float tmax, int channel, Sampler& sampler,
                     FlightRecord* record = nullptr) const override;
  Color transmittance(const Ray& ray, float tmax, Sampler& sampler) const override;
  const PhaseFunction& phase() const override { return *phase_; }
  Color sigma_s(const Vec3& p) const override;
  static std::unique_ptr<Medium> create(const Params& p);

 private:
  std::unique_ptr<Volume> sigma_t_, albedo_;
  float scale_, majorant_;
  std::unique_ptr<PhaseFunction> phase_;
  // The part of [0, tmax] inside the extinction's bounds; false where none is.
  bool clip(const Ray& ray, float tmax, float& t0, float& t1) const;
};

}  // namespace caustica
