// Unidirectional path tracer with next-event estimation.
#pragma once
#include "trace/integrator.h"

namespace caustica {

// max_depth, rr_depth and hide_emitters: nothing of its own.
using PathSettings = MonteCarloSettings;

// One path tracer's sample along a camera ray (PathIntegrator::Li; the photon integrator's
// pilot weighs it against its own samples, and renders with it where it is the better).
Color trace_path(const Ray& camera_ray, const Scene& scene, Sampler& sampler, const MonteCarloSettings& settings);
// The same through participating media (trace_path's, where the scene has any): free-flight
// sampling in each medium, phase-function vertices with their own shadow rays (MIS against the
// phase sample), shadow rays through media boundaries with their transmittance. Scattering in
// a medium is a vertex as a surface is (max_depth counts both, as Mitsuba's volpath does);
// passing a null boundary is none.
Color trace_volume_path(const Ray& camera_ray, const Scene& scene, Sampler& sampler, const MonteCarloSettings& settings);

class PathIntegrator final : public Integrator {
 public:
  explicit PathIntegrator(const PathSettings& settings) : settings_(settings) {}
  static std::unique_ptr<Integrator> create(const Params& p, const RenderSettings& render);
  Color Li(const Ray& ray, const Scene& scene, Sampler& sampler) const override;
  std::string name() const override { return "path"; }
  std::string describe() const override;

 private:
  PathSettings settings_;
};

}  // namespace caustica
