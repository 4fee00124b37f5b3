// Jensen's two-pass photon mapping (`photon`), and the global map viewed directly (`photon-direct`).
#pragma once
#include "photon/density.h"
#include "photon/photon_map.h"
#include "trace/integrator.h"

namespace caustica {

struct PhotonSettings : MonteCarloSettings {
  // Stored in the global and caustic maps: per pass when progressive (kProgressivePhotons).
  size_t photons = 200000;
  size_t caustic_photons = 200000;
  static constexpr size_t kProgressivePhotons = 100000;
  // Progressive and not given: per pass kPhotonsPerPixel of the image's pixels, between
  // kMinProgressivePhotons and kProgressivePhotons, set at preprocess (photons_for_image). The
  // photon pass then keeps its share of a pass's time at any image size (BENCHMARKS.md).
  bool photons_from_image = false, caustic_photons_from_image = false;
  static constexpr double kPhotonsPerPixel = 0.4;
  static constexpr size_t kMinProgressivePhotons = 10000;
  static size_t photons_for_image(int width, int height);
  int global_k = 50;
  int caustic_k = 80;
  float global_radius = 0;   // 0: chosen from the scene's area and the photon count
  float caustic_radius = 0;  // 0: likewise
  int gather_rays = 12;      // final-gather rays per first diffuse hit (tuned at equal time, BENCHMARKS.md)
  int direct_samples = 4;    // shadow-ray samples per first diffuse hit
  int irradiance_stride = 4; // precompute irradiance at every n-th global photon; 0: off
  // Photons are stored, and eye paths stop to gather, on a diffuse lobe or a glossy lobe at
  // least this rough (microfacet alpha); smoother glossy surfaces are traced through.
  float glossy_threshold = 0.3f;
  // Of the surfaces traced through, those with a delta lobe or glossy lobes smoother than this
  // carry caustic photons; light through the rougher (soft) ones is final-gathered, with shadow
  // rays at the soft vertex (gather.h).
  float caustic_threshold = 0.05f;
  // Progressive photon mapping (Knaus and Zwicker 2011): every pass traces fresh maps of the
  // counts above and estimates within fixed radii that shrink as r_i^2 = r_1^2 prod (j + alpha) / (j + 1).
  // The default since it measured better at equal time at 10 to 120 s (BENCHMARKS.md).
  bool progressive = true;
  float alpha = 2.0f / 3.0f;

  // Reads the integrator block (its keys were checked against the registry row).
  static PhotonSettings read(const Params& p, const RenderSettings& render, bool final_gather);
};

struct PhotonStats {
  double photon_seconds = 0, build_seconds = 0, irradiance_seconds = 0;  // summed over passes
  int passes = 0;  // photon passes traced
  uint64_t global_emitted = 0, caustic_emitted = 0;
  size_t global_bytes = 0, caustic_bytes = 0, irradiance_bytes = 0;
};

class PhotonIntegrator final : public Integrator {
 public:
  PhotonIntegrator(const PhotonSettings& settings, bool final_gather) : final_gather_(final_gather), settings_(settings) {}
  static std::unique_ptr<Integrator> create(const Params& p, const RenderSettings& render);
  // `photon-direct`: no final gathering, the global map seen directly.
  static std::unique_ptr<Integrator> create_direct(const Params& p, const RenderSettings& render);
  void preprocess(const Scene& scene, const PreprocessContext& context) override;
  bool progressive() const override { return settings_.progressive; }
  bool begin_pass(const Scene& scene, int pass, const PreprocessContext& context) override;
  Color Li(const Ray& ray, const Scene& scene, Sampler& sampler) const override;
  std::string name() const override { return final_gather_ ? "photon" : "photon-direct"; }
  std::string describe() const override;

  bool supports_aov() const override { return true; }
  const PhotonMap* global_map() const override { return &global_; }
  const PhotonMap* caustic_map() const override { return &caustic_; }
  const PhotonSettings& settings() const { return settings_; }
  const PhotonStats& stats() const { return stats_; }
  // The estimate settings in use after preprocess (radii resolved).
  const EstimateSettings& global_estimate() const { return global_est_; }
  const EstimateSettings& caustic_estimate() const { return caustic_est_; }

 private:
  // Traces and builds the maps with `seed`; false when cancelled.
  bool build_maps(const Scene& scene, uint64_t seed, const PreprocessContext& context);
  // Precomputes irradiance on the global map with the current radii.
  void build_irradiance();
  // Final gathering by BSDF samples from eye vertex `depth`; with skip_delta, samples of delta
  // lobes count 0.
  Color final_gather(const Scene& scene, const SurfaceHit& hit, const Vec3& wo, Sampler& sampler,
                     std::vector<Neighbour>& scratch, bool skip_delta, int depth) const;
  // Camera paths split at the first kSplitLevels glass surfaces into reflection and refraction.
  static constexpr int kSplitLevels = 2;
  Color trace_eye(const Ray& ray, const Scene& scene, Sampler& sampler, int depth, int splits_left) const;
  void record_aov(const SurfaceHit& hit, const Vec3& wo, float* aov, std::vector<Neighbour>& scratch) const;
  // The global map's estimate at eye vertex `depth`.
  Color indirect_at(const SurfaceHit& hit, const Vec3& wo, std::vector<Neighbour>& scratch, int depth) const;
  // The estimate settings for eye vertex `depth` (0: the camera ray's hit): photons of at most
  // max_depth - 1 - depth bounces, so that the joined path has at most max_depth + 1 segments,
  // as a `path` path has.
  EstimateSettings at_depth(const EstimateSettings& s, int depth) const {
    return with_bounces(s, 0, settings_.max_depth - 1 - depth);
  }

  // BSDF (gather) samples per shadow-ray sample at a gather point, for MIS; 0 without gathering.
  float gather_ratio() const {
    return final_gather_ && settings_.gather_rays > 0 ? float(settings_.gather_rays) / float(settings_.direct_samples) : 0.0f;
  }
  bool final_gather_;
  PhotonSettings settings_;
  PhotonStats stats_;
  PhotonMap global_, caustic_;
  IrradianceCache irradiance_;
  EstimateSettings global_est_, caustic_est_;
  float global_r1_ = 0, caustic_r1_ = 0;  // progressive: the first pass's radii
  int built_pass_ = -1;                   // progressive: the pass the maps were traced for
  std::vector<std::string> warnings_;
};

}  // namespace caustica
