// Unidirectional path tracer with next-event estimation.
#pragma once
#include "trace/integrator.h"

namespace caustica {

struct PathSettings {
  int max_depth = 16;  // from the render block
  int rr_depth = 3;    // Russian roulette starts after this many bounces
  bool hide_emitters = false;  // directly visible emitters (and the environment) render black
};

class PathIntegrator final : public Integrator {
 public:
  PathIntegrator(const JsonSource& settings, const RenderSettings& render);
  Color Li(const Ray& ray, const Scene& scene, Sampler& sampler) const override;
  std::string name() const override { return "path"; }
  std::string describe() const override;

 private:
  PathSettings settings_;
};

}  // namespace caustica
