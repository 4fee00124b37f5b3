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
  // The radiance along ray from eye vertex `depth` (0: the camera's), starting in `medium`.
  Color trace(Ray ray, const Scene& scene, Sampler& sampler, int depth, int32_t medium) const;
  // The segment [0, s) of ray through `medium` (ending on `end`, if any): adds the light
  // scattered once towards the eye to L (times beta) and takes beta on to the segment's end.
  // False when the path ends there (it scattered in a grid medium, or nothing passes).
  bool through_medium(const Ray& ray, float s, const SurfaceHit* end, const Scene& scene, int32_t medium,
                      Sampler& sampler, int depth, Color& L, Color& beta) const;
  int max_depth_;
};

}  // namespace caustica
