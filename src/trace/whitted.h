// Whitted-style integrator.
#pragma once
#include "trace/integrator.h"

namespace caustica {

class WhittedIntegrator final : public Integrator {
 public:
  explicit WhittedIntegrator(int max_depth) : max_depth_(max_depth) {}
  // No settings of its own; max_depth from the render block.
  static std::unique_ptr<Integrator> create(const Params& p, const RenderSettings& render);
  Color Li(const Ray& ray, const Scene& scene, Sampler& sampler) const override;
  std::string name() const override { return "whitted"; }
  std::string describe() const override;

 private:
  Color trace(const Ray& ray, const Scene& scene, Sampler& sampler, int depth) const;
  int max_depth_;
};

}  // namespace caustica
