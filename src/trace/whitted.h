// Whitted-style integrator.
#pragma once
#include "trace/integrator.h"

namespace caustica {

class WhittedIntegrator final : public Integrator {
 public:
  WhittedIntegrator(const JsonSource& settings, const RenderSettings& render);
  Color Li(const Ray& ray, const Scene& scene, Sampler& sampler) const override;
  std::string name() const override { return "whitted"; }
  std::string describe() const override;

 private:
  Color trace(const Ray& ray, const Scene& scene, Sampler& sampler, int depth) const;
  int max_depth_;
};

}  // namespace caustica
