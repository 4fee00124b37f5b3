// Stochastic progressive photon mapping (Hachisuka and Jensen 2009), as in pbrt: per pass, a
// fresh photon map, one visible point per pixel and per-pixel photon statistics whose radius
// shrinks; consistent, and the method users compare against. In participating media the eye
// path may end in a medium instead (a free flight that scatters): there the visible point
// gathers the volume photons within a ball, with statistics of its own.
#pragma once
#include <vector>
#include "photon/density.h"
#include "photon/photon_map.h"
#include "photon/volume_map.h"
#include "trace/integrator.h"

namespace caustica {

struct SppmSettings : MonteCarloSettings {
  size_t photons = 100000;  // stored per pass
  float radius = 0;         // first radius of every pixel; 0: an even spread's disc of 50 photons
  float alpha = 2.0f / 3.0f;  // fraction of a pass's photons kept in the statistics
  float glossy_threshold = 0.3f;  // as `photon`: where photons are stored and eye paths stop

  static SppmSettings read(const Params& p, const RenderSettings& render);
};

// One pixel's statistics (pbrt-v3's SPPMPixel): radius, photon count N, and flux tau.
struct SppmPixel {
  float radius = 0;
  double n = 0;
  glm::dvec3 tau{0.0};
  // Adds a pass's M photons with BSDF-weighted flux phi (beta included): N += alpha M, the
  // radius shrinks by sqrt(N_new / (N + M)) and tau keeps the flux inside the new radius.
  // In a medium (dimensions 3: photons in a ball) the radius shrinks by the cube root, and
  // phi is the radiance estimate times pi r^2 as on a surface, so that tau / (pi r^2) stays the
  // radiance: tau scales by the new radius's square over the old's.
  void add_pass(size_t m, const Color& phi, float alpha, int dimensions = 2);
};

class SppmIntegrator final : public Integrator {
 public:
  explicit SppmIntegrator(const SppmSettings& settings) : settings_(settings) {}
  static std::unique_ptr<Integrator> create(const Params& p, const RenderSettings& render);
  void preprocess(const Scene& scene, const PreprocessContext& context) override;
  bool progressive() const override { return true; }
  bool begin_pass(const Scene& scene, int pass, const PreprocessContext& context) override;
  // Per-pass radiance: emission and direct light at the visible point. Updates the pixel's
  // photon statistics (the render loop visits each pixel once per pass, on one thread).
  Color Li(const Ray& ray, const Scene& scene, Sampler& sampler) const override;
  // Adds the photon estimate tau / (passes pi r^2) to each pixel.
  void resolve(Image& mean, const std::vector<int>& pixel_passes) const override;
  bool passes_independent() const override { return false; }
  std::string name() const override { return "sppm"; }
  std::string describe() const override;

  const SppmSettings& settings() const { return settings_; }
  const std::vector<SppmPixel>& pixels() const { return pixels_; }
  // In media: each pixel's statistics of the passes whose visible point lay in a medium.
  const std::vector<SppmPixel>& volume_pixels() const { return volume_pixels_; }

 private:
  // The visible point at a surface / in a medium: adds their photons to the pixel's statistics
  // (`throughput` is the eye path's to the point).
  void gather_surface(const SurfaceHit& hit, const Vec3& wo, int depth, const Color& throughput, Sampler& sampler) const;
  void gather_volume(const Scene& scene, const Vec3& p, const Vec3& wo, int32_t medium, int depth,
                     const Color& throughput, Sampler& sampler) const;
  SppmSettings settings_;
  float radius0_ = 0;
  float volume_radius0_ = 0;  // in media: the first radius of the balls
  PhotonMap map_;
  VolumePhotonMap volume_;
  int passes_ = 0;
  double photon_seconds_ = 0;
  uint64_t emitted_ = 0;
  std::vector<std::string> warnings_;
  mutable std::vector<SppmPixel> pixels_, volume_pixels_;
};

}  // namespace caustica
