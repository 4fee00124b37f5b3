// Jensen's two-pass photon mapping (`photon`), and the global map viewed directly (`photon-direct`).
#pragma once
#include <chrono>
#include "photon/density.h"
#include "photon/photon_map.h"
#include "photon/volume_map.h"
#include "trace/integrator.h"

namespace caustica {

struct PhotonSettings : MonteCarloSettings {
  // Stored in the global and caustic maps: per pass when progressive (kProgressivePhotons).
  size_t photons = 200000;
  size_t caustic_photons = 200000;
  static constexpr size_t kProgressivePhotons = 100000;
  static constexpr size_t kMaxProgressivePhotons = 1000000;  // the pilot's choice at most
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
  int gather_rays = 12;      // final-gather rays per first diffuse hit
  int direct_samples = 4;    // shadow-ray samples per first diffuse hit
  // Shadow-ray samples at each glossy vertex of a camera path before its gather point (MIS
  // against the one BSDF sample that continues it).
  int glossy_direct_samples = 1;
  // Not given in the scene or on the command line (read() clears them): chosen for the scene
  // by a pilot before the render (PhotonIntegrator::choose_sample_counts).
  bool gather_rays_given = true, direct_samples_given = true, glossy_direct_samples_given = true;
  bool caustic_threshold_given = true;  // the pilot may choose 0 when not given
  // Indirect light at the first diffuse hit: final gathering (Jensen's), or the global map's
  // own estimate there (its photons of one bounce or more; the direct light stays the shadow
  // rays', and the global map holds the caustic paths too, so no caustic map is traced), as
  // SPPM views its maps. The second is cheap a sample and biased by the radii, which shrink
  // pass by pass: where the light bounces mostly between diffuse walls it converges faster.
  // Not given, the pilot measures both and keeps the one of less predicted error.
  bool final_gather = true;
  bool final_gather_given = true;
  // final_gather false, and what it implies: no gather rays, no caustic photons.
  void use_global_estimate();
  int irradiance_stride = 4; // precompute irradiance at 1 in n global photons (IrradianceCache); 0: off
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
  // Under a time budget, the image is path traced where the pilot predicts path tracing's error
  // at the budget below ours (and no caustic photons are stored).
  bool path_fallback = true;
  // In participating media (the scene has any): the volume photons' first radius, given or
  // holding volume_k of them (VolumePhotonMap::median_knn_radius), shrinking as the surfaces'.
  int volume_k = 30;
  float volume_radius = 0;
  // Each volume photon's kernel normalised over the part of its ball in its medium
  // (correct_volume_boundaries), so that walls and a medium's bounds do not darken it.
  bool volume_boundary = true;

  // Reads the integrator block (its keys were checked against the registry row).
  static PhotonSettings read(const Params& p, const RenderSettings& render, bool final_gather);
};

// What the pilot measured (choose_sample_counts), per camera sample: variances weighted as the
// relMSE weighs them, costs in rays (a photon-map estimate counted as kEstimateCost rays).
struct SampleCountPilot {
  bool ran = false;
  int samples = 0;        // camera samples traced
  double v_pixel = 0;     // variance left with exact direct light and gathers
  double v_direct = 0;    // of one shadow-ray sample (summed over a sample's gather points)
  double v_gather = 0;    // of one gather ray
  double v_glossy = 0;    // of one shadow ray at a glossy vertex (summed over a sample's)
  double v_maps = 0;      // the photon maps' (shared by a pass's samples; progressive only)
  double c_pixel = 0;     // cost of the rest of a sample
  double c_direct = 0, c_gather = 0, c_glossy = 0;
  double c_maps = 0;      // a pixel's share of a photon pass
  double photon_scale = 1;  // the photons per pass scaled by this (when not given)
  // The progressive radii's bias (measured when the photons are chosen and the render's length
  // is known): the relMSE-weighted squared bias of one pass's image at the first radii, from
  // estimates at three disc sizes with the same samples, and how it grows with the disc's
  // area (as (r^2)^bias_exponent, within 1/2 and 1; 1/4 and 1 for the estimate without final gathering); how the maps' variance grows as the radii
  // shrink (v_maps scales as (r^2)^-maps_growth); the passes the choice expects.
  bool measured_bias = false;
  double bias2 = 0, bias_exponent = 1, maps_growth = 0, horizon_passes = 0;
  double error = 0;  // the error at equal time the choice promises, times the work per sample
  double seconds_per_work = 0;  // the pilot samples' time over their work (all threads)
  // Whether the global map's estimate in place of the final gather was measured too, and the
  // two errors compared (as `error`).
  bool compared_final_gather = false;
  double final_gather_error = 0, estimate_error = 0;
  // Whether caustic_threshold 0 was measured too (choose_sample_counts).
  bool compared_caustic_threshold = false;
  // Under a time budget: the relMSE (weighted as above) the choice predicts at the budget's
  // end, and path tracing's there, from its own pilot samples on the same pixels; path_mode:
  // the image is path traced (PhotonSettings::path_fallback).
  double predicted_error = 0, path_error = 0, path_passes = 0;
  bool path_mode = false;
};

// Sample counts that minimise the error at equal time, (V0 + sum v_i / n_i)(C0 + sum n_i c_i),
// for parts of variance v_i and cost c_i per sample beside a fixed part (V0, C0):
// n_i = sqrt(v_i C0' / (V0' c_i)), with V0' and C0' the fixed part and the parts whose counts
// sit at a bound (the optimum efficiency-aware splitting builds on; Rath et al. 2022, "EARS",
// apply it per path vertex). A part of no variance or no cost gets its lower bound.
struct SampleCountPart {
  double v = 0, c = 0;     // variance and cost of one sample
  double lo = 1, hi = 64;  // bounds of the count
};
std::vector<double> optimal_sample_counts(double v0, double c0, const std::vector<SampleCountPart>& parts);

// Progressive photon mapping's error after `passes` passes, as the pilot models it: each pass
// has variance v_rest + v_maps S^-growth / scale and bias b (S / scale)^bias_exponent (bias2 =
// b^2), with S the pass's radius2 scale (progressive_radius2_scale) and `scale` the photons per
// pass's (the discs' area falls as 1 / scale); the image is the passes' mean, so the error is
// their mean variance / passes + (their mean bias)^2.
struct ProgressiveModel {
  double v_rest = 0, v_maps = 0, growth = 0, bias2 = 0, bias_exponent = 1;
};
double progressive_error(const ProgressiveModel& model, double scale, double passes, double alpha);

struct PhotonStats {
  double photon_seconds = 0, build_seconds = 0, irradiance_seconds = 0;  // summed over passes
  int passes = 0;  // photon passes traced for the image
  int pilot_passes = 0;  // and for the pilot (choose_sample_counts)
  uint64_t global_emitted = 0, caustic_emitted = 0;
  size_t global_bytes = 0, caustic_bytes = 0, irradiance_bytes = 0;
  size_t volume_photons = 0, volume_caustic_photons = 0;  // the last pass's
  double volume_caustic_share = 0;  // the last pass's (PhotonPassResult)
  size_t volume_bytes = 0;  // both volume maps'
};

class PhotonIntegrator final : public Integrator {
 public:
  PhotonIntegrator(const PhotonSettings& settings, bool final_gather) : final_gather_(final_gather), settings_(settings) {}
  static std::unique_ptr<Integrator> create(const Params& p, const RenderSettings& render);
  // `photon-direct`: no final gathering, the global map seen directly.
  static std::unique_ptr<Integrator> create_direct(const Params& p, const RenderSettings& render);
  void preprocess(const Scene& scene, const PreprocessContext& context) override;
  bool progressive() const override { return settings_.progressive && !pilot_.path_mode; }
  bool begin_pass(const Scene& scene, int pass, const PreprocessContext& context) override;
  Color Li(const Ray& ray, const Scene& scene, Sampler& sampler) const override;
  std::string name() const override { return final_gather_ ? "photon" : "photon-direct"; }
  std::string describe() const override;

  bool supports_aov() const override { return true; }
  const PhotonMap* global_map() const override { return &global_; }
  const PhotonMap* caustic_map() const override { return &caustic_; }
  std::vector<const PhotonMap*> volume_maps() const override {
    if (!media_) return {};
    return {&volume_.photons(), &volume_caustic_.photons()};
  }
  const VolumePhotonMap& volume_map() const { return volume_; }
  const VolumePhotonMap& volume_caustic_map() const { return volume_caustic_; }
  // The volume maps' radii in the current pass.
  float volume_radius() const { return volume_r1_ * std::sqrt(volume_radius2_scale_); }
  float volume_caustic_radius() const { return volume_caustic_r1_ * std::sqrt(volume_radius2_scale_); }
  const PhotonSettings& settings() const { return settings_; }
  const PhotonStats& stats() const { return stats_; }
  const SampleCountPilot& pilot() const { return pilot_; }
  // The pilot's bounds: shadow rays and gather rays per gather point, the photons' scale.
  static constexpr int kMaxSampleCount = 64;
  // Path tracing is taken only where its predicted error is below ours by this factor: on six
  // public scenes the two predictions each erred by up to 2x against the errors measured at
  // 30 s (BENCHMARKS.md), so a closer call is no call.
  static constexpr double kPathFallbackMargin = 1.5;
  // Likewise the global map's estimate in place of final gathering (final_gather not given):
  // on Mitsuba's test_various_emitters it was predicted 1.28x better and measured 1.6x worse
  // at 30 s; on the scenes where it measured better it was predicted 2.5x to 9x better.
  static constexpr double kEstimateMargin = 1.5;
  // The pilot's range of photon scales (and at least kMinProgressivePhotons / 16 photons). Down
  // to 1/32: under environment maps the maps add little variance, and at the former 1/8 the
  // photon passes were a tenth of a render of Mitsuba's copper matpreview.
  static constexpr double kMinPhotonScale = 1.0 / 32.0, kMaxPhotonScale = 8.0;
  // The estimate settings in use after preprocess (radii resolved).
  const EstimateSettings& global_estimate() const { return global_est_; }
  const EstimateSettings& caustic_estimate() const { return caustic_est_; }

 private:
  // Traces and builds the maps with `seed`; false when cancelled.
  bool build_maps(const Scene& scene, uint64_t seed, const PreprocessContext& context);
  // Precomputes irradiance on the global map with the current radii.
  void build_irradiance();
  // Records, for the pilot, each shadow-ray and gather sample of a camera sample.
  struct Probe;
  // Chooses gather_rays and direct_samples, where not given, for the least relMSE per unit of
  // work: a pilot of camera samples over the image measures the variance of one shadow ray,
  // of one gather ray and of the rest of a sample, and what each costs; the optimum of
  // (V0 + Vd / nd + Vg / ng)(C0 + nd Cd + ng Cg) is nd = sqrt(Vd C0 / (V0 Cd)), likewise ng.
  // Deterministic: the same counts for any thread count.
  // Progressive, with the photon counts not given, it also scales the photons per pass: their
  // maps' variance (measured on two passes' maps) and cost scale with them. False when cancelled.
  bool choose_sample_counts(const Scene& scene, const PreprocessContext& context);
  // One pilot with the settings as they are: measures, sets the counts (and the photons when
  // choose_photons), and gives the error at equal time they promise. False when cancelled.
  bool pilot_and_choose(const Scene& scene, const PreprocessContext& context, bool choose_photons, double& error);
  // The estimates' photons per disc (k) as `factor` times the settings', and the precomputed
  // irradiance for them.
  void set_disc_photons(int factor);
  // Under a time budget, the render's work per pixel the pilot expects (-1: not yet taken), set
  // by the first pilot so that a second one is weighed at the same.
  double horizon_work_ = -1;
  double horizon_seconds_ = 0;  // and the seconds (all ranks') it was taken from
  // Path tracing's relMSE at the budget's end (SampleCountPilot::path_error), from
  // kPathPilotPerPixel samples at each pilot pixel, timed.
  static constexpr int kPathPilotPerPixel = 16;
  double pilot_path_error(const Scene& scene, uint64_t seed, double& passes) const;
  std::chrono::steady_clock::time_point preprocess_start_;
  // The pilot: kPilotPerPixel camera samples at each pixel of a grid over the image.
  static constexpr int kPilotGrid = 64, kPilotPerPixel = 4;
  // The parts of a camera sample whose counts the pilot chooses: shadow rays at gather points,
  // gather rays, shadow rays at glossy vertices.
  enum PilotPart { kPilotDirect, kPilotGather, kPilotGlossy, kPilotParts };
  struct PilotSample {
    double value = 0;  // the sample's luminance
    // each part's i-th sample (Probe) and the work of all of them
    double part[kPilotParts][4] = {};
    double work = 0, part_work[kPilotParts] = {};
  };
  std::vector<PilotSample> pilot_samples(const Scene& scene, uint64_t seed) const;
  // Final gathering by BSDF samples from eye vertex `depth`; with skip_delta, samples of delta
  // lobes count 0. n rays, MIS against shadow rays taken at `ratio` per gather ray.
  Color final_gather(const Scene& scene, const SurfaceHit& hit, const Vec3& wo, Sampler& sampler,
                     std::vector<Neighbour>& scratch, bool skip_delta, int depth, int n, float ratio,
                     const Color& beta, Probe* probe) const;
  // Camera paths split at the first kSplitLevels glass surfaces into reflection and refraction.
  static constexpr int kSplitLevels = 2;
  Color trace_eye(const Ray& ray, const Scene& scene, Sampler& sampler, int depth, int splits_left,
                  Probe* probe = nullptr) const;
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
  SampleCountPilot pilot_;
  double photon_pass_cost_ = 0;  // the last photon pass's cost in rays (pilot)
  PhotonMap global_, caustic_;
  // In media (media_): the eye path (trace_media_eye) takes the global map's estimate at its
  // gather point (no final gathering, no surface caustic map: the global map holds caustics),
  // shadow rays through the media, and along every segment through a medium the beam radiance
  // estimate of the volume maps (the light scattered once more than the photons had) beside a
  // shadow ray from one point of it (single scattering). photon-direct: no shadow rays, the
  // maps' photons straight from the lights too (PhotonPassSettings::volume_direct).
  bool media_ = false;
  Color trace_media_eye(const Ray& ray, const Scene& scene, Sampler& sampler) const;
  // The in-scattered radiance towards -ray.dir along [0, tmax] of ray in `medium` from eye
  // vertex `depth`: volume photons of one bounce or more (photon-direct: of any) projecting onto it, each weighted by
  // `weight(t)` (the transmittance to it); `segment_end` (>= tmax) ends the medium's segment,
  // where a photon's kernel is cut off. `open_start`: the ray starts inside the medium (at the
  // camera), not at a surface, and the photons just behind it whose balls reach it count too.
  template <class W>
  Color beam_estimate(const Ray& ray, float tmax, float segment_end, bool open_start, const Scene& scene,
                      int32_t medium, int depth, W&& weight) const;
  VolumePhotonMap volume_, volume_caustic_;
  float volume_r1_ = 0, volume_caustic_r1_ = 0, volume_radius2_scale_ = 1;
  bool volume_radii_set_ = false;
  IrradianceCache irradiance_;
  EstimateSettings global_est_, caustic_est_;
  float global_r1_ = 0, caustic_r1_ = 0;  // progressive: the first pass's radii
  int built_pass_ = -1;                   // progressive: the pass the maps were traced for
  std::vector<std::string> warnings_;
};

}  // namespace caustica
