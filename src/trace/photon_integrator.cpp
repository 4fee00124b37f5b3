// Photon mapping eye pass: at the first diffuse hit, direct light by shadow rays, caustics
// from the caustic map, indirect light by final gathering into the global map (Jensen 1996).
#include "trace/photon_integrator.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include "photon/gather.h"
#include "photon/photon_tracer.h"
#include "photon/volume_boundary.h"
#include "trace/eye_path.h"
#include "trace/path.h"

namespace caustica {
namespace {
thread_local std::vector<Neighbour> tls_scratch;
// Work counted for the pilot (choose_sample_counts) in rays: a photon-map estimate (k nearest
// photons) and a precomputed-irradiance lookup as so many rays, and a stored photon's share of
// the kd-tree build and the precomputation. Counted, not timed, so that the pilot chooses the
// same counts on every run; the weights are measured (BENCHMARKS.md, issue 25).
struct Work {
  uint64_t estimates = 0;   // photon-map estimates
  uint64_t neighbours = 0;  // photons their searches returned (each evaluates the BSDF)
  uint64_t lookups = 0;     // precomputed-irradiance lookups
};
thread_local Work tls_work;
// (Fitted to the time per camera sample's parts on eleven scenes, with a scale per scene for
// its ray cost; the photon pass's to its parts' times on the same scenes.)
constexpr double kEstimateCost = 1.5, kNeighbourCost = 0.35, kLookupCost = 1.0;
constexpr double kPhotonRayCost = 1.3, kStoredPhotonCost = 1.2;
// The counts so far on this thread; work_since(sampler, w) is the work done since snapshot w,
// from the counts' integer differences (the same whatever the thread did before).
struct WorkSnapshot {
  uint64_t rays;
  Work work;
};
WorkSnapshot work_snapshot(const Sampler& sampler) { return {sampler.rays, tls_work}; }
double work_since(const Sampler& sampler, const WorkSnapshot& w0) {
  const Work& w = tls_work;
  return double(sampler.rays - w0.rays) + kEstimateCost * double(w.estimates - w0.work.estimates) +
         kNeighbourCost * double(w.neighbours - w0.work.neighbours) + kLookupCost * double(w.lookups - w0.work.lookups);
}
// A photon-map estimate, counted.
Color counted_estimate(const PhotonMap& map, const SurfaceHit& hit, const Vec3& wo, const EstimateSettings& s,
                       std::vector<Neighbour>& scratch) {
  EstimateInfo info;
  const Color L = radiance_estimate(map, hit, wo, s, scratch, &info);
  ++tls_work.estimates;
  tls_work.neighbours += info.found;
  return L;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The unbiased sample variance of n values.
double sample_variance(const double* v, int n) {
  double mean = 0, ss = 0;
  for (int i = 0; i < n; ++i) mean += v[i];
  mean /= n;
  for (int i = 0; i < n; ++i) ss += (v[i] - mean) * (v[i] - mean);
  return ss / (n - 1);
}

// Each pilot pixel's weight as the relMSE weighs its error, 1 / (reference^2 + 0.01), with the
// mean of the neighbouring pilot pixels' samples for the reference (values: m per pixel of a
// gx x gy grid, row by row): the pixel's own would let its outliers shrink its weight, and
// their variance with it. Sums in pixel order: the same for any thread count.
std::vector<double> pilot_weights(const std::vector<double>& values, int gx, int gy, int m) {
  std::vector<double> weights(size_t(gx) * size_t(gy));
  for (int y = 0; y < gy; ++y)
    for (int x = 0; x < gx; ++x) {
      double sum = 0;
      int count = 0;
      for (int ny = std::max(0, y - 1); ny <= std::min(gy - 1, y + 1); ++ny)
        for (int nx = std::max(0, x - 1); nx <= std::min(gx - 1, x + 1); ++nx) {
          if (nx == x && ny == y) continue;
          for (int j = 0; j < m; ++j) sum += values[(size_t(ny) * size_t(gx) + size_t(nx)) * size_t(m) + size_t(j)];
          count += m;
        }
      const double mean = count > 0 ? sum / count : 0.0;
      weights[size_t(y) * size_t(gx) + size_t(x)] = 1.0 / (mean * mean + 0.01);
    }
  return weights;
}
// The pilot's camera ray through pixel cell of a gx x gy grid over the image (the pixel at the
// cell's centre), jittered with the sampler's first numbers.
Ray pilot_ray(const Scene& scene, int cell, int gx, int gy, Sampler& sampler) {
  const int w = scene.camera.width(), h = scene.camera.height();
  const int x = ((cell % gx) * w + w / 2) / gx, y = ((cell / gx) * h + h / 2) / gy;
  const Vec2 jitter = sampler.next2d();
  return scene.camera.has_lens() ? scene.camera.generate_ray(x, y, jitter, sampler.next2d())
                                 : scene.camera.generate_ray(x, y, jitter);
}
}  // namespace

PhotonSettings PhotonSettings::read(const Params& p, const RenderSettings& render, bool final_gather) {
  PhotonSettings s;
  static_cast<MonteCarloSettings&>(s) = read_monte_carlo(p, render);
  // photon-direct shows one photon map as it is, unless asked otherwise.
  s.progressive = p.boolean("progressive", final_gather);
  // Progressive passes each trace their own maps: fewer photons per pass do better at equal
  // time there (BENCHMARKS.md, "Progressive photon mapping").
  if (s.progressive) s.photons = s.caustic_photons = kProgressivePhotons;
  auto integer = [&](const char* key, auto& field, int64_t lo, int64_t hi) {
    field = static_cast<std::decay_t<decltype(field)>>(p.integer(key, int64_t(field), lo, hi));
  };
  auto number = [&](const char* key, float& field) { field = float(p.number_in(key, field, 0.0, 1e30)); };
  s.photons_from_image = s.progressive && !p.has("photons");
  s.caustic_photons_from_image = s.progressive && !p.has("caustic_photons");
  integer("photons", s.photons, 0, int64_t(1) << 31);
  integer("caustic_photons", s.caustic_photons, 0, int64_t(1) << 31);
  integer("global_k", s.global_k, 1, 10000);
  integer("caustic_k", s.caustic_k, 1, 10000);
  number("global_radius", s.global_radius);
  number("caustic_radius", s.caustic_radius);
  integer("gather_rays", s.gather_rays, 0, 1 << 16);
  integer("direct_samples", s.direct_samples, 1, 1 << 16);
  integer("glossy_direct_samples", s.glossy_direct_samples, 1, 1 << 16);
  s.gather_rays_given = !final_gather || p.has("gather_rays");
  s.direct_samples_given = !final_gather || p.has("direct_samples");
  s.glossy_direct_samples_given = !final_gather || p.has("glossy_direct_samples");
  s.caustic_threshold_given = !final_gather || p.has("caustic_threshold");
  s.final_gather = !final_gather || p.boolean("final_gather", true);
  // Keys of final gathering's given: they say which estimator is wanted.
  s.final_gather_given = !final_gather || p.has("final_gather") || !s.progressive || p.has("gather_rays") ||
                         p.has("caustic_photons") || p.has("caustic_k") || p.has("caustic_radius");
  if (!s.final_gather) s.use_global_estimate();
  integer("irradiance_stride", s.irradiance_stride, 0, 1 << 20);
  number("glossy_threshold", s.glossy_threshold);
  number("caustic_threshold", s.caustic_threshold);
  s.alpha = float(p.number_in("alpha", s.alpha, 1e-3, 0.999));
  s.path_fallback = final_gather && p.boolean("path_fallback", true);
  integer("volume_k", s.volume_k, 1, 10000);
  number("volume_radius", s.volume_radius);
  s.volume_boundary = p.boolean("volume_boundary", true);
  return s;
}

void PhotonSettings::use_global_estimate() {
  final_gather = false;
  gather_rays = 0;
  gather_rays_given = true;
  caustic_photons = 0;
  caustic_photons_from_image = false;
}

size_t PhotonSettings::photons_for_image(int width, int height) {
  const double wanted = kPhotonsPerPixel * double(std::max(width, 1)) * double(std::max(height, 1));
  return std::clamp(size_t(wanted), kMinProgressivePhotons, kProgressivePhotons);
}

std::unique_ptr<Integrator> PhotonIntegrator::create(const Params& p, const RenderSettings& render) {
  return std::make_unique<PhotonIntegrator>(PhotonSettings::read(p, render, true), true);
}

std::unique_ptr<Integrator> PhotonIntegrator::create_direct(const Params& p, const RenderSettings& render) {
  return std::make_unique<PhotonIntegrator>(PhotonSettings::read(p, render, false), false);
}

void PhotonIntegrator::preprocess(const Scene& scene, const PreprocessContext& context) {
  preprocess_start_ = std::chrono::steady_clock::now();
  horizon_work_ = -1;
  volume_r1_ = volume_caustic_r1_ = 0.0f;
  volume_radii_set_ = false;
  volume_radius2_scale_ = 1.0f;
  horizon_seconds_ = 0;
  const size_t for_image = PhotonSettings::photons_for_image(scene.camera.width(), scene.camera.height());
  if (settings_.photons_from_image) settings_.photons = for_image;
  if (settings_.caustic_photons_from_image) settings_.caustic_photons = for_image;
  media_ = scene.has_media();
  if (media_) {
    // In media the eye path takes the global map's estimate (trace_media_eye); the caustic
    // photons go to the volume caustic map alone. No pilot: its models know no media.
    const size_t volume_caustic = settings_.caustic_photons;
    settings_.use_global_estimate();
    settings_.caustic_photons = volume_caustic;
    settings_.path_fallback = false;
    settings_.gather_rays_given = settings_.direct_samples_given = settings_.glossy_direct_samples_given = true;
    settings_.final_gather_given = settings_.caustic_threshold_given = true;
  }
  // (In media the volume map may hold up to kVolumeShare times the global photons.)
  const size_t volume_share = scene.has_media() ? PhotonPassSettings::kVolumeShare : 0;
  check_photon_memory(settings_.photons * (1 + volume_share) + (final_gather_ ? settings_.caustic_photons : 0));
  global_est_.k = size_t(settings_.global_k);
  caustic_est_.k = size_t(settings_.caustic_k);
  caustic_est_.cone_filter = true;
  // Radii from the photon density on the scene's surfaces: a disc holding k photons if they
  // were spread evenly. A progressive pass estimates within fixed radii, shrinking from these;
  // otherwise they bound the k-NN search, 3x wider for the global map (it also covers dim regions).
  const float area = std::max(scene.surface_area(), 1e-12f);
  auto even_radius = [&](int k, size_t photons) {
    return std::sqrt(float(k) * area / (kPi * float(std::max<size_t>(photons, 1))));
  };
  if (settings_.progressive) {
    auto first_radii = [&] {
      global_r1_ = settings_.global_radius > 0 ? settings_.global_radius
                                               : 3.0f * even_radius(settings_.global_k, settings_.photons);
      caustic_r1_ = settings_.caustic_radius > 0 ? settings_.caustic_radius
                                                 : even_radius(settings_.caustic_k, settings_.caustic_photons);
    };
    first_radii();
    // The pilot runs on passes 0 and 1's maps on every MPI rank, so that all choose alike.
    built_pass_ = -1;
    const size_t photons = settings_.photons, caustic_photons = settings_.caustic_photons;
    if (!media_ && !choose_sample_counts(scene, context)) return;
    // The volume maps' first radii come from pass 0's maps on every MPI rank, so that all
    // render alike.
    if (media_ && context.first_pass != 0 && !build_maps(scene, context.seed, context)) return;
    if (settings_.photons != photons || settings_.caustic_photons != caustic_photons) {
      first_radii();
      built_pass_ = -1;  // the pilot's maps had the other counts
    } else if (built_pass_ == 0 && context.first_pass == 0) {
      --stats_.pilot_passes, ++stats_.passes;  // its pass 0 is the image's
    }
    // The first pass's maps now (so that `caustica photons` and the AOVs see maps); the others
    // in begin_pass.
    begin_pass(scene, context.first_pass, context);
    return;
  }
  if (!build_maps(scene, context.seed, context)) return;
  global_est_.max_radius = settings_.global_radius > 0 ? settings_.global_radius
                                                       : 3.0f * even_radius(settings_.global_k, global_.size());
  caustic_est_.max_radius = settings_.caustic_radius > 0 ? settings_.caustic_radius
                                                         : even_radius(settings_.caustic_k, caustic_.size());
  build_irradiance();
  if (!media_) choose_sample_counts(scene, context);
}

bool PhotonIntegrator::begin_pass(const Scene& scene, int pass, const PreprocessContext& context) {
  if (!settings_.progressive || pass == built_pass_ || pilot_.path_mode) return true;
  // Each estimate's disc (the k nearest photons', at most the first radii) shrinks by the
  // schedule: per pass the same adaptive disc as without progression, scaled.
  const float scale2 = float(progressive_radius2_scale(pass, settings_.alpha));
  global_est_.max_radius = global_r1_;
  caustic_est_.max_radius = caustic_r1_;
  global_est_.radius2_scale = caustic_est_.radius2_scale = volume_radius2_scale_ = scale2;
  // Pass i's photons come from their own seed: the image is the same for any thread count.
  const uint64_t seed = pass == 0 ? context.seed : hash_seed(context.seed, uint64_t(pass), 0x70706d);  // "ppm"
  if (!build_maps(scene, seed, context)) return false;
  build_irradiance();
  built_pass_ = pass;
  return true;
}

void PhotonIntegrator::set_disc_photons(int factor) {
  global_est_.k = size_t(settings_.global_k) * size_t(factor);
  caustic_est_.k = size_t(settings_.caustic_k) * size_t(factor);
  const double pass_cost = photon_pass_cost_;  // (the pass's cost is its maps' and first precomputation's)
  build_irradiance();
  photon_pass_cost_ = pass_cost;
}

void PhotonIntegrator::build_irradiance() {
  irradiance_ = IrradianceCache{};  // never a previous pass's
  if (!final_gather_ || !settings_.final_gather || settings_.irradiance_stride <= 0 || global_.empty()) return;
  const auto t0 = std::chrono::steady_clock::now();
  // For the gathers' points at eye vertices 1 .. 8 (gathers from eye vertices 0 .. 7).
  irradiance_.build(global_, size_t(settings_.irradiance_stride), at_depth(global_est_, 1), 8);
  // Each point's k-NN search, as an estimate's.
  photon_pass_cost_ += (kEstimateCost + kNeighbourCost * double(global_est_.k)) * double(irradiance_.size());
  stats_.irradiance_seconds += seconds_since(t0);
  stats_.irradiance_bytes = irradiance_.memory_bytes();
}

bool PhotonIntegrator::build_maps(const Scene& scene, uint64_t seed, const PreprocessContext& context) {
  PhotonPassSettings pass;
  pass.global_photons = settings_.photons;
  pass.caustic_photons = final_gather_ ? settings_.caustic_photons : 0;
  pass.caustic_volume_only = media_;
  pass.volume_direct = media_ && !final_gather_;
  pass.max_depth = settings_.max_depth;
  pass.glossy_threshold = settings_.glossy_threshold;
  pass.caustic_threshold = final_gather_ ? settings_.caustic_threshold : pass.caustic_threshold;
  pass.seed = seed;
  pass.cancel = context.cancel;
  PhotonPassResult r = trace_photons(scene, pass);
  stats_.photon_seconds += r.seconds;
  photon_pass_cost_ = kPhotonRayCost * double(r.rays) + kStoredPhotonCost * double(r.global.size() + r.caustic.size());
  stats_.global_emitted += r.global_emitted;
  stats_.caustic_emitted += r.caustic_emitted;
  ++stats_.passes;
  report_new_warnings(r.warnings, warnings_, context.quiet);
  if (context.cancel && context.cancel->load()) return false;  // the maps of a stopped pass are empty
  auto t0 = std::chrono::steady_clock::now();
  // The two kd-tree builds are serial inside nanoflann: side by side they take one's time.
  tbb::parallel_invoke([&] { global_.build(std::move(r.global), r.global_scale); },
                       [&] { caustic_.build(std::move(r.caustic), r.caustic_scale); });
  stats_.build_seconds += seconds_since(t0);
  stats_.global_bytes = global_.memory_bytes();
  stats_.caustic_bytes = caustic_.memory_bytes();
  if (media_) {
    t0 = std::chrono::steady_clock::now();
    stats_.volume_photons = r.volume.size();
    stats_.volume_caustic_photons = r.volume_caustic.size();
    stats_.volume_caustic_share = r.volume_caustic_share;
    tbb::parallel_invoke([&] { volume_.build(std::move(r.volume), r.volume_scale); },
                         [&] { volume_caustic_.build(std::move(r.volume_caustic), r.volume_caustic_scale); });
    stats_.build_seconds += seconds_since(t0);
    stats_.volume_bytes = volume_.memory_bytes() + volume_caustic_.memory_bytes();
    // The first radii from the first maps, pass 0's on every rank (each map its own: a volume
    // caustic is far denser); a map too sparse for one takes the other's, or a hundredth of the
    // scene's size.
    if (!volume_radii_set_) {
      volume_radii_set_ = true;
      const size_t k = size_t(settings_.volume_k);
      volume_r1_ = settings_.volume_radius > 0 ? settings_.volume_radius : volume_.median_knn_radius(k);
      volume_caustic_r1_ = settings_.volume_radius > 0 ? settings_.volume_radius : volume_caustic_.median_knn_radius(k);
      const float fallback = 0.005f * glm::length(scene.bounds().extent());
      if (!(volume_r1_ > 0.0f)) volume_r1_ = volume_caustic_r1_ > 0.0f ? volume_caustic_r1_ : fallback;
      if (!(volume_caustic_r1_ > 0.0f)) volume_caustic_r1_ = volume_r1_;
    }
    // Each photon's kernel over the part of its ball in its medium, at this pass's radii.
    if (settings_.volume_boundary) {
      t0 = std::chrono::steady_clock::now();
      const uint64_t rays = correct_volume_boundaries(volume_, scene, volume_radius(), seed) +
                            correct_volume_boundaries(volume_caustic_, scene, volume_caustic_radius(), hash_seed(seed, 1));
      photon_pass_cost_ += kPhotonRayCost * double(rays);
      stats_.build_seconds += seconds_since(t0);
    }
  }

  return !(context.cancel && context.cancel->load());
}

Color PhotonIntegrator::indirect_at(const SurfaceHit& hit, const Vec3& wo, std::vector<Neighbour>& scratch,
                                    int depth) const {
  const EstimateSettings est = at_depth(global_est_, depth);
  if (est.max_bounces < 0) return Color(0.0f);
  const Vec3 n_side = glm::dot(wo, hit.n) >= 0 ? hit.n : -hit.n;
  const int level = irradiance_.size() > 0 ? irradiance_.level_for(est) : -1;
  // (Bump- and normal-mapped diffuse surfaces too: their full estimate cost most of a render on
  // Mitsuba's principled scene, and the tilt changes a gather's second bounce very little.)
  if (level >= 0 && hit.material->diffuse_in_some_frame()) {
    Color E;
    // A progressive pass also shrinks how far away the precomputed point may lie.
    ++tls_work.lookups;
    if (irradiance_.lookup(hit.p, n_side, est.max_radius * std::sqrt(est.radius2_scale), level, E, scratch)) return hit.material->albedo(hit.sp) * kInvPi * E;
  }
  return counted_estimate(global_, hit, wo, est, scratch);
}

// One camera sample's shadow-ray and gather samples, by index, as they add to the pixel: the
// i-th samples of all its gather points summed (luminance), and the work they took.
struct PhotonIntegrator::Probe {
  static constexpr int kSamples = 4;
  static_assert(kSamples == std::size(PilotSample{}.part[0]));
  Color scale{1.0f};  // the throughput into the trace_eye call recording (glass splits, coats)
  double sum[kPilotParts][kSamples] = {};
  double work[kPilotParts] = {};
  void record(PilotPart part, int i, const Color& v, double w) {
    sum[part][i] += double(luminance(scale * v));
    work[part] += w;
  }
  // While a nested trace_eye runs: its samples count times `factor`.
  struct Nested {
    Probe* probe;
    Color saved;
    Nested(Probe* p, const Color& factor) : probe(p), saved(p ? p->scale : Color(1.0f)) {
      if (p) p->scale *= factor;
    }
    ~Nested() {
      if (probe) probe->scale = saved;
    }
    Nested(const Nested&) = delete;
    Nested& operator=(const Nested&) = delete;
  };
};

Color PhotonIntegrator::final_gather(const Scene& scene, const SurfaceHit& hit, const Vec3& wo, Sampler& sampler,
                                     std::vector<Neighbour>& scratch, bool skip_delta, int eye_depth, int n,
                                     float ratio, const Color& beta, Probe* probe) const {
  if (n <= 0) return Color(0.0f);
  const Vec3 wo_l = hit.frame.to_local(wo);
  // Stratified over an sx x sy grid; the remainder unstratified. (Not for the pilot: it takes
  // the variance of one ray from the spread of independent ones.)
  const int sx = std::max(1, int(std::sqrt(float(n)))), sy = n / sx;
  // One gather ray's contribution.
  auto gather_ray = [&](int i) -> Color {
    Vec2 u = sampler.next2d();
    if (i < sx * sy && !probe) u = Vec2((float(i % sx) + u.x) / float(sx), (float(i / sx) + u.y) / float(sy));
    BsdfSample bs;
    if (!hit.material->sample(wo_l, u, sampler.next1d(), bs, hit.sp)) return Color(0.0f);
    if (skip_delta && bs.delta) return Color(0.0f);  // the caller traces the delta lobes
    const Vec3 wi = hit.frame.to_world(bs.wi);
    if (hit.leaks(wi)) return Color(0.0f);
    Color sum(0.0f), throughput = radiance_weight(*hit.material, wo_l, bs, hit.sp);
    Ray ray = spawn_ray(hit.p, hit.n, wi);
    BsdfVertex from{bs.delta, ratio * bs.pdf, hit.p, hit.frame.n};
    // The emission a segment reaches is the gather's when the segment starts at the gather
    // point (direct light, shared with the shadow rays by MIS) or when a soft surface lies
    // between; through caustic surfaces alone it is the caustic map's.
    bool counts_emission = true, past_soft = false, traced_glossy = false;
    // The gather ray's vertices are eye vertices eye_depth + 1, + 2, ...; at eye vertex
    // max_depth only the last segment's emission still fits in the path.
    for (int depth = 0; eye_depth + 1 + depth <= settings_.max_depth; ++depth) {
      SurfaceHit g;
      ++sampler.rays;
      if (!scene.intersect(ray, g)) {
        if (counts_emission) sum += throughput * escaped_mis(scene, ray.dir, from);
        break;
      }
      const Bsdf& m = *g.material;
      if (counts_emission)
        sum += throughput * emission_mis(scene, g, scene.emitted(g, g.frame.to_local(-ray.dir)), from);
      if (eye_depth + 1 + depth == settings_.max_depth) break;
      // A gather ray's first glossy (not diffuse) gather surface is traced through as a path
      // tracer would, a shadow ray there and the estimate at the next surface: a glossy radiance
      // estimate weighs every photon in its disc by the BSDF, and on Mitsuba's principled scene
      // those estimates were most of the k-NN time (BENCHMARKS.md). From the second on, the
      // estimate (a room of rough metal would otherwise path-trace every gather ray).
      // The light it reflects is then a path tracer's: its shadow ray, and the emission the
      // next segment reaches MIS-weighted against it (past_soft).
      // (Not one with a delta coat: its gather passes the coat on below.)
      const bool gather_surface = is_gather_surface(m, settings_.glossy_threshold);
      const bool trace_glossy =
          gather_surface && !traced_glossy && !m.diffuse_in_some_frame() && !m.has(kBsdfSpecular);
      if (trace_glossy) traced_glossy = past_soft = true;
      if (gather_surface && !trace_glossy) {
        sum += throughput * indirect_at(g, -ray.dir, scratch, eye_depth + 1 + depth);
        // The photon estimate has no delta part: a coat (plastic) passes the gather ray on, as
        // the caustic map's photons pass through it; the emission it reaches is the caustic map's.
        BsdfSample coat;
        const Vec3 cwo = g.frame.to_local(-ray.dir);
        if (!delta_continuation(m, cwo, g.sp, [&] { return sampler.next1d(); }, coat)) break;
        const Vec3 cwi = g.frame.to_world(coat.wi);
        if (g.leaks(cwi)) break;
        throughput *= radiance_weight(m, cwo, coat, g.sp);
        from = BsdfVertex{};
        counts_emission = past_soft;
        ray = spawn_ray(g.p, g.n, cwi);
        continue;
      }
      const Vec3 gwo = -ray.dir;
      // From a soft surface on, the gather path is a path tracer's: shadow rays at its glossy
      // vertices, MIS-weighted against the emission the next segment reaches.
      past_soft = past_soft || !is_caustic_surface(m, settings_.caustic_threshold);
      if (past_soft && !m.is_specular()) sum += throughput * estimate_direct(scene, g, gwo, sampler, 1.0f);
      BsdfSample ss;
      const Vec2 us = sampler.next2d();
      const Vec3 gwo_l = g.frame.to_local(gwo);
      if (!m.sample(gwo_l, us, sampler.next1d(), ss, g.sp)) break;
      const Vec3 gwi = g.frame.to_world(ss.wi);
      if (g.leaks(gwi)) break;
      throughput *= radiance_weight(m, gwo_l, ss, g.sp);
      from = BsdfVertex{ss.delta, ss.pdf, g.p, g.frame.n};
      counts_emission = past_soft;
      ray = spawn_ray(g.p, g.n, gwi);
    }
    return sum;
  };
  Color total(0.0f);
  for (int i = 0; i < n; ++i) {
    const WorkSnapshot work0 = probe ? work_snapshot(sampler) : WorkSnapshot{};
    const Color one = gather_ray(i);
    total += one;
    if (probe) probe->record(kPilotGather, i, beta * one, work_since(sampler, work0));
  }
  return total / float(n);
}

void PhotonIntegrator::record_aov(const SurfaceHit& hit, const Vec3& wo, float* aov,
                                  std::vector<Neighbour>& scratch) const {
  EstimateInfo g, c;
  radiance_estimate(global_, hit, wo, global_est_, scratch, &g);
  if (!caustic_.empty()) radiance_estimate(caustic_, hit, wo, caustic_est_, scratch, &c);
  aov[0] = float(g.photons);
  aov[1] = float(c.photons);
  aov[2] = g.radius;
  aov[3] = c.radius;
}

Color PhotonIntegrator::Li(const Ray& camera_ray, const Scene& scene, Sampler& sampler) const {
  if (pilot_.path_mode) return trace_path(camera_ray, scene, sampler, settings_);
  if (media_) return trace_media_eye(camera_ray, scene, sampler);
  return trace_eye(camera_ray, scene, sampler, 0, kSplitLevels);
}

Color PhotonIntegrator::trace_eye(const Ray& start, const Scene& scene, Sampler& sampler, int depth,
                                  int splits_left, Probe* probe) const {
  std::vector<Neighbour>& scratch = tls_scratch;
  // Emission and the environment count in full after the camera and delta bounces; after a
  // near-specular glossy bounce they are weighted against that vertex's shadow ray (MIS).
  EyePath path{Color(0.0f), Color(1.0f), BsdfVertex{}, settings_.max_depth, settings_.hide_emitters};
  Color& L = path.L;
  const Color& beta = path.beta;
  Ray ray = start;
  for (;; ++depth) {
    SurfaceHit hit;
    if (!path.meet(scene, ray, depth, sampler, hit)) break;
    const Vec3 wo = -ray.dir;
    const Vec3 wo_l = hit.frame.to_local(wo);
    const Bsdf& m = *hit.material;
    if (is_gather_surface(m, settings_.glossy_threshold)) {
      if (sampler.aov) record_aov(hit, wo, sampler.aov, scratch);
      if (!final_gather_) return L + beta * radiance_estimate(global_, hit, wo, at_depth(global_est_, depth), scratch);
      // Direct light: shadow rays, MIS-weighted against the final-gather rays, which are BSDF
      // samples and count the emission their first segment reaches (final_gather).
      // (The pilot takes Probe::kSamples of each.)
      const int nd = probe ? Probe::kSamples : settings_.direct_samples;
      const bool gathering = settings_.final_gather;
      const int ng = probe ? Probe::kSamples : settings_.gather_rays;
      const float ratio = !gathering ? 0.0f : probe ? 1.0f : gather_ratio();
      // Stratified, except for the pilot (it takes one sample's variance from their spread).
      const StratifiedDirect lights(sampler, probe ? 1 : nd);
      Color direct(0.0f);
      for (int i = 0; i < nd; ++i) {
        const WorkSnapshot work0 = probe ? work_snapshot(sampler) : WorkSnapshot{};
        const Color one = lights.estimate(scene, hit, wo, sampler, i, ratio);
        direct += one;
        if (probe) probe->record(kPilotDirect, i, beta * one, work_since(sampler, work0));
      }
      L += beta * direct / float(nd);
      if (!caustic_.empty()) L += beta * counted_estimate(caustic_, hit, wo, at_depth(caustic_est_, depth), scratch);
      // A delta lobe beside the diffuse one (plastic's coat): traced as the eye path goes on,
      // while the final gather covers the other lobes only. Without splits left, the gather's
      // delta samples carry it instead; without the gather, one of the delta lobes is then
      // followed, chosen by its weight, and none with the probability of their sum's shortfall
      // from 1 (Russian roulette: the chain of coats ends). Where the BSDF cannot list its delta
      // lobes (more than two: glass under a coat), the gather's delta samples carry them; without
      // the gather, one BSDF sample is followed when it is a delta one (its weight is the lobe's
      // over its chance, so its mean is the delta lobes' part and no more).
      const bool has_coat = m.has(kBsdfSpecular);
      BsdfSample coat[2];
      int n_coat = has_coat && (splits_left > 0 || !gathering) ? m.specular_lobes(wo_l, coat, hit.sp) : 0;
      if (!gathering && has_coat && n_coat == 0) {
        n_coat = delta_continuation(m, wo_l, hit.sp, [&] { return sampler.next1d(); }, coat[0]) ? 1 : 0;
      } else if (!gathering && splits_left == 0 && n_coat > 0) {
        float p[2] = {max_component(coat[0].weight), n_coat > 1 ? max_component(coat[1].weight) : 0.0f};
        const float total = std::max(p[0] + p[1], 1.0f);
        const float u = sampler.next1d() * total;
        const int pick = u < p[0] ? 0 : u < p[0] + p[1] ? 1 : -1;
        n_coat = 0;
        if (pick >= 0 && p[pick] > 0.0f) {
          coat[0] = coat[pick];
          coat[0].weight /= p[pick] / total;
          n_coat = 1;
        }
      }
      for (int i = 0; i < n_coat; ++i) coat[i].weight = radiance_weight(m, wo_l, coat[i], hit.sp);
      const bool trace_coat = n_coat > 0;  // (gathering, listed only with splits left)
      if (gathering) {
        L += beta * final_gather(scene, hit, wo, sampler, scratch, trace_coat, depth, ng, ratio, beta, probe);
      } else {
        // The global map's photons of one bounce or more (the direct light is the shadow rays').
        const EstimateSettings est = at_depth(global_est_, depth);
        if (est.max_bounces >= 1)
          L += beta * counted_estimate(global_, hit, wo, with_bounces(est, 1, est.max_bounces), scratch);
      }
      if (trace_coat) {
        for (int i = 0; i < n_coat; ++i) {
          const Vec3 wi = hit.frame.to_world(coat[i].wi);
          if (is_black(coat[i].weight) || hit.leaks(wi)) continue;
          const Probe::Nested nested(probe, beta * coat[i].weight);
          L += beta * coat[i].weight * trace_eye(spawn_ray(hit.p, hit.n, wi), scene, sampler, depth + 1, std::max(splits_left - 1, 0), probe);
        }
      }
      return L;
    }
    BsdfSample lobes[2];
    if (splits_left > 0 && m.is_specular() && m.specular_lobes(wo_l, lobes, hit.sp) == 2) {
      // Follow both reflection and refraction, weighted by Fresnel, instead of choosing one
      // at random: choosing leaves bright speckles (the light reflected in the glass) that
      // take many samples to average out.
      Color split(0.0f);
      for (BsdfSample& lobe : lobes) {
        lobe.weight = radiance_weight(m, wo_l, lobe, hit.sp);
        if (is_black(lobe.weight)) continue;
        const Ray next = spawn_ray(hit.p, hit.n, hit.frame.to_world(lobe.wi));
        const Probe::Nested nested(probe, beta * lobe.weight);
        split += lobe.weight * trace_eye(next, scene, sampler, depth + 1, splits_left - 1, probe);
      }
      return L + beta * split;
    }
    // A glossy lobe below the gather threshold: direct light by shadow rays, MIS-weighted
    // against the BSDF sample that continues the path.
    const int n = m.is_specular() ? 0 : probe ? Probe::kSamples : settings_.glossy_direct_samples;
    const StratifiedDirect lights(sampler, probe ? 1 : n);
    for (int i = 0; i < n; ++i) {
      const WorkSnapshot work0 = probe ? work_snapshot(sampler) : WorkSnapshot{};
      const Color one = lights.estimate(scene, hit, wo, sampler, i, 1.0f / float(n));
      L += beta * one / float(n);
      if (probe) probe->record(kPilotGlossy, i, beta * one, work_since(sampler, work0));
    }
    if (!path.scatter(hit, wo, sampler, ray)) break;
    if (n > 1) path.from.pdf /= float(n);  // one BSDF sample against n light samples
  }
  return L;
}

std::vector<double> optimal_sample_counts(double v0, double c0, const std::vector<SampleCountPart>& parts) {
  const size_t n = parts.size();
  std::vector<double> count(n);
  for (size_t i = 0; i < n; ++i) count[i] = parts[i].lo;
  // Coordinate descent: each count in turn is set to its optimum with the others held, the
  // sqrt rule with the others in the fixed part, clamped. The error is a product of posynomials,
  // convex in log n, so within the bounds' box this converges to the one optimum.
  for (int round = 0; round < 200; ++round) {
    double change = 0;
    for (size_t i = 0; i < n; ++i) {
      const SampleCountPart& p = parts[i];
      if (!(p.v > 0) || !(p.c > 0)) continue;  // stays at lo
      double v = v0, c = c0;
      for (size_t j = 0; j < n; ++j)
        if (j != i) v += parts[j].v / count[j], c += parts[j].c * count[j];
      const double best = std::clamp(v > 0 ? std::sqrt(p.v * c / (v * p.c)) : p.hi, p.lo, p.hi);
      change = std::max(change, std::abs(best - count[i]) / count[i]);
      count[i] = best;
    }
    if (change < 1e-9) break;
  }
  return count;
}

namespace {
// The means over passes 0 .. n - 1 of S(p)^bias_exponent and of S(p)^-growth, with S(p) the
// radius2 scale: Gamma(p + 1 + alpha) / (Gamma(1 + alpha) Gamma(p + 2)) (the product in
// progressive_radius2_scale), so long horizons are summed in blocks of p / 128 passes at their
// middle pass's value.
struct ProgressiveMeans {
  double bias = 1, inverse = 1;
};
ProgressiveMeans progressive_means(double n, double alpha, double growth, double bias_exponent) {
  const double lg0 = std::lgamma(1.0 + alpha);
  auto log_scale = [&](double p) { return std::lgamma(p + 1.0 + alpha) - lg0 - std::lgamma(p + 2.0); };
  double sum = 0, sum_inverse = 0;
  for (double p = 0; p < n;) {
    const double len = std::min(n - p, std::max(1.0, std::floor(p / 128.0)));
    const double ls = log_scale(p + 0.5 * (len - 1.0));
    sum += len * std::exp(bias_exponent * ls);
    sum_inverse += len * std::exp(-growth * ls);
    p += len;
  }
  return {sum / n, sum_inverse / n};
}
}  // namespace

double progressive_error(const ProgressiveModel& m, double scale, double passes, double alpha) {
  const double n = std::floor(std::clamp(passes, 1.0, 1e9));
  const ProgressiveMeans mean = progressive_means(n, alpha, m.growth, m.bias_exponent);
  return (m.v_rest + m.v_maps * mean.inverse / scale) / n +
         m.bias2 * mean.bias * mean.bias / std::pow(scale, 2.0 * m.bias_exponent);
}

std::vector<PhotonIntegrator::PilotSample> PhotonIntegrator::pilot_samples(const Scene& scene, uint64_t seed) const {
  const int w = scene.camera.width(), h = scene.camera.height();
  const int gx = std::min(w, kPilotGrid), gy = std::min(h, kPilotGrid);
  std::vector<PilotSample> out(size_t(gx) * size_t(gy) * kPilotPerPixel);
  const uint64_t pilot_seed = hash_seed(seed, 0x70696c6f74, 0);  // "pilot"
  tbb::parallel_for(0, gx * gy, [&](int cell) {
    for (int j = 0; j < kPilotPerPixel; ++j) {
      Sampler sampler(hash_seed(uint64_t(cell), uint64_t(j), pilot_seed));
      const Ray ray = pilot_ray(scene, cell, gx, gy, sampler);
      Probe probe;
      const WorkSnapshot work0 = work_snapshot(sampler);
      const double v = double(luminance(trace_eye(ray, scene, sampler, 0, kSplitLevels, &probe)));
      PilotSample& r = out[size_t(cell) * kPilotPerPixel + size_t(j)];
      r.value = std::isfinite(v) ? v : 0.0;
      for (int k = 0; k < kPilotParts; ++k) {
        for (int i = 0; i < Probe::kSamples; ++i) r.part[k][i] = std::isfinite(probe.sum[k][i]) ? probe.sum[k][i] : 0.0;
        r.part_work[k] = probe.work[k];
      }
      r.work = work_since(sampler, work0);
    }
  });
  return out;
}

bool PhotonIntegrator::choose_sample_counts(const Scene& scene, const PreprocessContext& context) {
  const bool choose_photons = settings_.progressive && (settings_.photons_from_image || settings_.caustic_photons_from_image);
  if (!final_gather_ || (settings_.gather_rays_given && settings_.direct_samples_given &&
                         settings_.glossy_direct_samples_given && !choose_photons))
    return true;
  const PhotonSettings asked = settings_;
  double error = 0;
  if (!pilot_and_choose(scene, context, choose_photons, error)) return false;
  // The pilot once more with the asked settings changed by `change`: kept (1) where its error
  // times `margin` is below the choice so far, which is restored otherwise (0); -1: stopped.
  auto weigh = [&](auto change, double margin, double& changed_error) {
    const PhotonSettings with = settings_;
    const SampleCountPilot with_pilot = pilot_;
    settings_ = asked;
    change(settings_);
    built_pass_ = -1;
    if (!pilot_and_choose(scene, context, choose_photons, changed_error)) return -1;
    if (margin * changed_error < error) {
      error = changed_error;
      return 1;
    }
    settings_ = with;
    pilot_ = with_pilot;
    built_pass_ = -1;  // the maps are the other choice's
    return 0;
  };
  // Caustics through near-specular glossy surfaces: the caustic map's estimate at every gather
  // point can cost more than it saves (a k-NN search where few caustic photons lie). The
  // other way, caustic_threshold 0, leaves them to the final gather (shadow rays at the glossy
  // vertex); the pilot measures both and keeps the one of less error at equal time.
  // (Only where some surface is such: with none, the two are the same.)
  auto near_specular = [&](const std::unique_ptr<Bsdf>& m) {
    return !is_gather_surface(*m, settings_.glossy_threshold) && !m->has(kBsdfSpecular) &&
           is_caustic_surface(*m, settings_.caustic_threshold);
  };
  if (settings_.progressive && !settings_.caustic_threshold_given && settings_.caustic_threshold > 0 &&
      !caustic_.empty() && std::any_of(scene.materials.begin(), scene.materials.end(), near_specular)) {
    double error_without = 0;
    if (weigh([](PhotonSettings& s) { s.caustic_threshold = 0; }, 1.0, error_without) < 0) return false;
    pilot_.compared_caustic_threshold = true;
  }
  // The caustic map last traced: after the comparison above, caustic_threshold 0's whichever was
  // kept (so caustics through delta surfaces alone: near-specular glossy ones path tracing
  // renders too, and its predicted error says how well). Without the comparison, no surface is
  // near-specular and the two maps are the same. (With final_gather false given, no caustic map
  // is traced to tell: taken as there being some.)
  const bool caustic_paths = !caustic_.empty() || !settings_.final_gather;
  // The global map's estimate at the first diffuse hit instead of the final gather (no caustic
  // map then: the global map holds those paths): measured where the radii's bias is (it is
  // most of that estimate's error), and kept where its predicted error is the less by
  // kEstimateMargin.
  if (!settings_.final_gather_given && settings_.photons_from_image && pilot_.measured_bias) {
    const bool compared_threshold = pilot_.compared_caustic_threshold;
    const double error_gather = error;
    double error_estimate = 0;
    if (weigh([](PhotonSettings& s) { s.use_global_estimate(); }, kEstimateMargin, error_estimate) < 0) return false;
    pilot_.compared_caustic_threshold = compared_threshold;
    pilot_.compared_final_gather = true;
    pilot_.final_gather_error = error_gather;
    pilot_.estimate_error = error_estimate;
  }
  // Under a time budget, path tracing's error at its end, predicted from its own samples on the
  // pilot's pixels, against ours.
  if (settings_.path_fallback && pilot_.measured_bias && context.time_budget > 0 && horizon_seconds_ > 0) {
    pilot_.path_error = pilot_path_error(scene, context.seed, pilot_.path_passes);
    if (context.cancel && context.cancel->load()) return false;
    pilot_.path_mode = !caustic_paths && kPathFallbackMargin * pilot_.path_error < pilot_.predicted_error;
    if (pilot_.path_mode) {
      global_ = PhotonMap();
      caustic_ = PhotonMap();
      irradiance_ = IrradianceCache();
    }
  }
  return true;
}

double PhotonIntegrator::pilot_path_error(const Scene& scene, uint64_t seed, double& passes) const {
  constexpr int M = kPathPilotPerPixel;
  const int w = scene.camera.width(), h = scene.camera.height();
  const int gx = std::min(w, kPilotGrid), gy = std::min(h, kPilotGrid);
  std::vector<double> values(size_t(gx) * size_t(gy) * M);
  const uint64_t path_seed = hash_seed(seed, 0x70617468, 0);  // "path"
  const auto t0 = std::chrono::steady_clock::now();
  tbb::parallel_for(0, gx * gy, [&](int cell) {
    for (int j = 0; j < M; ++j) {
      Sampler sampler(hash_seed(uint64_t(cell), uint64_t(j), path_seed));
      const Ray ray = pilot_ray(scene, cell, gx, gy, sampler);
      const double v = double(luminance(trace_path(ray, scene, sampler, settings_)));
      values[size_t(cell) * M + size_t(j)] = std::isfinite(v) ? v : 0.0;
    }
  });
  const double seconds_per_sample = seconds_since(t0) / double(values.size());
  // Weighted as the photon pilot weighs its pixels (pilot_weights), summed in pixel order.
  const std::vector<double> weights = pilot_weights(values, gx, gy, M);
  double variance = 0;
  for (size_t px = 0; px < weights.size(); ++px) variance += weights[px] * sample_variance(&values[px * M], M);
  variance /= double(weights.size());
  passes = std::max(1.0, horizon_seconds_ / (seconds_per_sample * double(w) * double(h)));
  return variance / passes;
}

bool PhotonIntegrator::pilot_and_choose(const Scene& scene, const PreprocessContext& context, bool choose_photons,
                                        double& error) {
  constexpr int P = Probe::kSamples, M = kPilotPerPixel;
  // The bias of the progressive radii, where the photons are chosen and the render's length is
  // known (the bias falls with the passes, the variance with the samples): the same samples
  // once more on each pass's maps with kWide times the photons per disc (k), so kWide times its
  // area. Taking the bias as growing with r^2 (as Knaus and Zwicker 2011 do), the difference
  // is kWide - 1 times a pass's bias; the product of two maps' differences has no map noise in
  // it. (Wider, not narrower, discs: a disc of k / 4 photons is so noisy that the difference
  // drowned in the maps' noise, 5x apart between seeds on env-preview.)
  const bool measure_bias = settings_.progressive && choose_photons && (context.passes > 0 || context.time_budget > 0);
  constexpr int kWide = 4;
  // Progressive: the same samples on pass 1's maps and then on pass 0's tell the part of the
  // variance that is the maps' own (a pass's maps are shared by all its pixels' samples, so
  // the spread of one map's samples misses it).
  std::vector<PilotSample> other, other_mid, other_wide, samples_mid, samples_wide;
  // The same samples on the current maps with 2 and kWide times the photons per disc.
  auto wider_discs = [&](std::vector<PilotSample>& mid, std::vector<PilotSample>& wide) {
    set_disc_photons(2);
    mid = pilot_samples(scene, context.seed);
    set_disc_photons(kWide);
    wide = pilot_samples(scene, context.seed);
    set_disc_photons(1);
  };
  const int passes = stats_.passes;
  float other_scale2 = 1.0f;
  if (settings_.progressive) {
    if (!begin_pass(scene, 1, context)) return false;
    other = pilot_samples(scene, context.seed);
    other_scale2 = global_est_.radius2_scale;
    if (measure_bias) wider_discs(other_mid, other_wide);
    if (!begin_pass(scene, 0, context)) return false;
    // The pilot's photon passes are its own (pass 0's maps serve the render if their counts
    // stay: preprocess).
    stats_.pilot_passes += stats_.passes - passes;
    stats_.passes = passes;
  }
  const auto t_samples = std::chrono::steady_clock::now();
  const std::vector<PilotSample> samples = pilot_samples(scene, context.seed);
  const double samples_seconds = seconds_since(t_samples);
  if (measure_bias) wider_discs(samples_mid, samples_wide);
  if (context.cancel && context.cancel->load()) return false;
  // Sums in pixel order: the same for any thread count.
  SampleCountPilot r;
  r.ran = true;
  r.samples = int(samples.size());
  double work = 0, part_work[kPilotParts] = {}, v_maps_wide = 0, bias_44 = 0, bias_24 = 0;
  const size_t pixels = samples.size() / M;
  const int gx = std::min(scene.camera.width(), kPilotGrid), gy = int(pixels) / gx;
  std::vector<double> sample_values(samples.size());
  for (size_t i = 0; i < samples.size(); ++i) sample_values[i] = samples[i].value;
  const std::vector<double> weights = pilot_weights(sample_values, gx, gy, M);
  // The maps' variance in a camera sample, from the same samples on two passes' maps: the mean
  // of the gather rays' differences has the per-ray part of the maps' noise (already in the
  // gather rays' spread) over P; the rest is shared.
  auto maps_variance = [&](const PilotSample& a, const PilotSample& b) {
    double d[P];
    for (int i = 0; i < P; ++i) d[i] = a.part[kPilotGather][i] - b.part[kPilotGather][i];
    const double e = a.value - b.value;
    return 0.5 * e * e - 0.5 * sample_variance(d, P) / P;
  };
  for (size_t px = 0; px < pixels; ++px) {
    const PilotSample* s = &samples[px * M];
    double v_part[kPilotParts] = {}, v_maps = 0, v_wide = 0;
    for (int j = 0; j < M; ++j) {
      work += s[j].work;
      for (int k = 0; k < kPilotParts; ++k) {
        v_part[k] += sample_variance(s[j].part[k], P) / M;
        part_work[k] += s[j].part_work[k];
      }
      if (!other.empty()) v_maps += maps_variance(s[j], other[px * M + size_t(j)]) / M;
      if (measure_bias) v_wide += maps_variance(samples_wide[px * M + size_t(j)], other_wide[px * M + size_t(j)]) / M;
    }
    const double weight = weights[px];
    // Between one map's camera samples: V0 + (Vd + Vg + Vs) / P.
    r.v_pixel += weight * (sample_variance(&sample_values[px * M], M) - (v_part[kPilotDirect] + v_part[kPilotGather] + v_part[kPilotGlossy]) / P);
    r.v_direct += weight * v_part[kPilotDirect];
    r.v_gather += weight * v_part[kPilotGather];
    r.v_glossy += weight * v_part[kPilotGlossy];
    r.v_maps += weight * v_maps;
    if (measure_bias) {
      // Each sample's differences with 2 and 4 times the photons per disc, on either map. A
      // product of two on different maps and different camera samples has no noise of either
      // in its expectation (the pixel's bias terms' product): the mean of all such pairs.
      auto cross = [&](const std::vector<PilotSample>& a_wide, const std::vector<PilotSample>& a,
                       const std::vector<PilotSample>& b_wide, const std::vector<PilotSample>& b) {
        double sum_a = 0, sum_b = 0, same = 0;
        for (int j = 0; j < M; ++j) {
          const size_t i = px * M + size_t(j);
          const double da = a_wide[i].value - a[i].value, db = b_wide[i].value - b[i].value;
          sum_a += da, sum_b += db, same += da * db;
        }
        return (sum_a * sum_b - same) / (M * (M - 1));
      };
      bias_44 += weight * cross(samples_wide, samples, other_wide, other);
      bias_24 += weight * 0.5 * (cross(samples_mid, samples, other_wide, other) + cross(samples_wide, samples, other_mid, other));
      v_maps_wide += weight * v_wide;
    }
  }
  for (double* v : {&r.v_pixel, &r.v_direct, &r.v_gather, &r.v_glossy, &r.v_maps, &v_maps_wide, &bias_44, &bias_24})
    *v /= double(pixels);
  r.v_maps = std::max(r.v_maps, 0.0);
  const double n = double(samples.size());
  r.c_direct = part_work[kPilotDirect] / (n * P);
  r.c_gather = part_work[kPilotGather] / (n * P);
  r.c_glossy = part_work[kPilotGlossy] / (n * P);
  r.c_pixel = (work - part_work[kPilotDirect] - part_work[kPilotGather] - part_work[kPilotGlossy]) / n;
  // The photon pass is traced once per image pass: each pixel's sample carries its share.
  const int w = scene.camera.width(), h = scene.camera.height();
  r.c_maps = settings_.progressive ? photon_pass_cost_ / (double(w) * double(h)) : 0.0;
  if (measure_bias) {
    r.measured_bias = true;
    // With the bias b (k / k1)^e at k photons a disc (k1 the settings'), the two products
    // are b^2 (4^e - 1)^2 and b^2 (2^e - 1)(4^e - 1): their ratio is 2^e + 1. e = 1 where the
    // light bends smoothly (bias as r^2), 1/2 at its edges (as r) where gather rays read the
    // estimates: a gather integrates over the band along an edge that its discs reach across,
    // and that band's width is r. Where the image shows the estimate itself (final_gather
    // false), a pixel in the band is biased by a share of its disc that does not shrink with r,
    // and the band's share of the pixels is r: the squared bias summed over the image as r,
    // e = 1/4. Taken within those. (With 1/2 there, Mitsuba's cbox was predicted 2x better with
    // the estimate and measured 1.46x worse.)
    const double lowest = settings_.final_gather ? 0.5 : 0.25;
    r.bias_exponent = bias_44 > 0 && bias_24 > 0 ? std::clamp(std::log2(std::max(bias_44 / bias_24 - 1.0, 1e-9)), lowest, 1.0) : 1.0;
    // Pass 1's maps are read at its radii, other_scale2 of pass 0's.
    const double spread = std::pow(double(kWide), r.bias_exponent) - 1.0;
    r.bias2 = std::max(bias_44, 0.0) / (spread * spread * std::pow(double(other_scale2), r.bias_exponent));
    // The maps' variance at the discs' area against at kWide times it.
    r.maps_growth = r.v_maps > 0 && v_maps_wide > 0 ? std::clamp(std::log(r.v_maps / v_maps_wide) / std::log(double(kWide)), 0.0, 1.0) : 0.0;
  }

  // The counts not given, for the least error at equal time (optimal_sample_counts); those
  // given (and the photons, when not chosen) join the fixed part.
  double v0 = r.v_pixel, c0 = r.c_pixel;
  std::vector<SampleCountPart> parts;
  int* counts[3] = {&settings_.direct_samples, &settings_.gather_rays, &settings_.glossy_direct_samples};
  const bool given[3] = {settings_.direct_samples_given, settings_.gather_rays_given,
                         settings_.glossy_direct_samples_given};
  const double v[3] = {r.v_direct, r.v_gather, r.v_glossy}, c[3] = {r.c_direct, r.c_gather, r.c_glossy};
  for (int i = 0; i < 3; ++i) {
    if (!given[i]) parts.push_back({v[i], c[i], 1.0, double(kMaxSampleCount)});
    else if (*counts[i] > 0) v0 += v[i] / *counts[i], c0 += c[i] * *counts[i];
  }
  if (!choose_photons) v0 += r.v_maps, c0 += r.c_maps;
  // V0 is never taken as below a hundredth of the rest (noise in the pilot's difference can
  // make it 0 or negative).
  v0 = std::max(v0, 0.01 * (r.v_direct + r.v_gather + r.v_glossy + r.v_maps));
  // The counts' variance and work per sample, with the photons scaled by x (the maps' variance
  // and cost both scale with the photons per pass).
  // The maps' variance in one pass's sample, averaged over the passes (it grows as the radii
  // shrink), with the photons scaled by x.
  auto v_maps_per_sample = [&](double x, double passes) {
    const ProgressiveModel maps{0, r.v_maps, r.maps_growth, 0, 1};
    return progressive_error(maps, x, passes, settings_.alpha) * std::floor(std::max(passes, 1.0));
  };
  auto per_sample = [&](const std::vector<double>& chosen, double x, double& ve, double& ce) {
    ve = v0, ce = c0 + (choose_photons ? r.c_maps * x : 0.0);
    for (size_t i = 0; i < parts.size(); ++i) ve += parts[i].v / chosen[i], ce += parts[i].c * chosen[i];
  };
  // Without the bias: the least variance times work per sample (the maps a part like the rest).
  std::vector<SampleCountPart> with_maps = parts;
  if (choose_photons) with_maps.push_back({r.v_maps, r.c_maps, kMinPhotonScale, kMaxPhotonScale});
  std::vector<double> chosen = optimal_sample_counts(v0, c0, with_maps);
  double x = choose_photons ? chosen.back() : 1.0;
  if (choose_photons) chosen.pop_back();
  double ve = 0, ce = 0;
  per_sample(chosen, x, ve, ce);
  error = (ve + (choose_photons ? r.v_maps / x : 0.0)) * ce;
  if (r.measured_bias) {
    // Under a time budget, the render's work per pixel: the budget (less the time spent so
    // far) at the pilot's rate of work, kept for a second pilot (choose_sample_counts) so that
    // both choices are weighed alike. Given passes, those.
    const bool timed = context.time_budget > 0;
    if (timed && horizon_work_ < 0) {
      const double rate = samples_seconds > 0 ? work / samples_seconds : 0.0;  // work per second
      const double left = std::max(0.0, context.time_budget * std::max(1, context.ranks) - seconds_since(preprocess_start_));
      horizon_work_ = std::max(ce, left * rate / (double(w) * double(h)));
      horizon_seconds_ = left;
    }
    // For each photon scale on a grid: the counts for its variance at the passes it will
    // take (a fixed point under a budget, as the maps' variance grows with the passes) and the
    // error there; under a budget the least error, given passes the least error times the
    // work (the error at equal time).
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 64; ++i) {
      const double xi = kMinPhotonScale * std::pow(kMaxPhotonScale / kMinPhotonScale, i / 64.0);
      double passes_i = timed ? 1.0 : double(context.passes);
      std::vector<double> ci;
      double vi = 0, cw = 0;
      for (int it = 0; it < (timed ? 4 : 1); ++it) {
        const double grown = v_maps_per_sample(xi, passes_i);
        ci = optimal_sample_counts(v0 + grown, c0 + r.c_maps * xi, parts);
        per_sample(ci, xi, vi, cw);
        if (timed) passes_i = std::max(1.0, horizon_work_ / cw);
      }
      const double e = progressive_error({vi, r.v_maps, r.maps_growth, r.bias2, r.bias_exponent}, xi, passes_i, settings_.alpha);
      const double score = timed ? e : e * cw;
      if (score < best) best = score, x = xi, chosen = ci, r.horizon_passes = passes_i;
    }
    r.predicted_error = timed ? best : 0.0;
    // In the units of the error without the bias (variance times work per sample).
    error = best * (timed ? horizon_work_ : double(context.passes));
  }
  for (int i = 0, next = 0; i < 3; ++i)
    if (!given[i]) *counts[i] = int(std::lround(chosen[size_t(next++)]));
  r.error = error;
  r.seconds_per_work = work > 0 ? samples_seconds / work : 0.0;
  pilot_ = r;
  if (choose_photons) {
    pilot_.photon_scale = x;
    auto scaled = [&](size_t photons) {
      return std::clamp(size_t(double(photons) * x), PhotonSettings::kMinProgressivePhotons / 16,
                        PhotonSettings::kMaxProgressivePhotons);
    };
    if (settings_.photons_from_image) settings_.photons = scaled(settings_.photons);
    if (settings_.caustic_photons_from_image) settings_.caustic_photons = scaled(settings_.caustic_photons);
    check_photon_memory(settings_.photons + settings_.caustic_photons);
  }
  return true;
}

std::string PhotonIntegrator::describe() const {
  std::ostringstream s;
  const size_t ng = global_.size(), nc = caustic_.size();
  s << "photons (global, wanted): " << settings_.photons << "\n";
  if (final_gather_) s << "caustic photons (wanted): " << settings_.caustic_photons << "\n";
  s << "global map: " << ng << " stored, k " << global_est_.k << ", max radius " << global_est_.max_radius << "\n";
  if (final_gather_) {
    s << "caustic map: " << nc << " stored, k " << caustic_est_.k << ", max radius " << caustic_est_.max_radius << ", cone filter k " << caustic_est_.cone_k << "\n";
    s << "indirect light at the first diffuse hit: "
      << (settings_.final_gather ? "final gathering" : "the global map's estimate (no caustic map)");
    if (pilot_.compared_final_gather)
      s << " (pilot: error at equal time " << pilot_.final_gather_error << " gathering, " << pilot_.estimate_error
        << " with the estimate)";
    s << "\n";
    s << "gather rays: " << settings_.gather_rays << (settings_.gather_rays_given ? "" : " (pilot)")
      << "\ndirect samples: " << settings_.direct_samples << (settings_.direct_samples_given ? "" : " (pilot)")
      << "\nglossy direct samples: " << settings_.glossy_direct_samples
      << (settings_.glossy_direct_samples_given ? "" : " (pilot)") << "\n";
    if (pilot_.ran)
      s << "pilot, per camera sample (" << pilot_.samples << "; relMSE-weighted variance, work in rays): the rest "
        << pilot_.v_pixel << ", " << pilot_.c_pixel << "; a shadow ray " << pilot_.v_direct << ", " << pilot_.c_direct
        << "; a gather ray " << pilot_.v_gather << ", " << pilot_.c_gather << "; a glossy vertex's shadow ray "
        << pilot_.v_glossy << ", " << pilot_.c_glossy << "; the photon maps " << pilot_.v_maps
        << ", " << pilot_.c_maps << " (photons scaled by " << pilot_.photon_scale << "); error at equal time "
        << pilot_.error << "\n";
    if (pilot_.measured_bias)
      s << "pilot, the progressive radii's bias: squared at the first radii " << pilot_.bias2
        << " (relMSE-weighted), growing as (r^2)^" << pilot_.bias_exponent << "; the maps' variance as (r^2)^-"
        << pilot_.maps_growth << "; for "
        << std::lround(pilot_.horizon_passes) << " passes expected\n";
    if (pilot_.path_error > 0)
      s << "pilot, relMSE predicted at the budget's end: " << pilot_.predicted_error << " (ours, " << std::lround(pilot_.horizon_passes)
        << " passes), " << pilot_.path_error << " (path tracing, " << std::lround(pilot_.path_passes) << " passes)" << (pilot_.path_mode ? ": the image is path traced (path_fallback)" : "") << "\n";
    if (pilot_.compared_caustic_threshold)
      s << "caustic threshold: " << settings_.caustic_threshold << " (the pilot's choice of it and 0)\n";
    s << "precomputed irradiance: " << (settings_.irradiance_stride > 0 ? "1 in " + std::to_string(std::max(2, settings_.irradiance_stride)) + " global photons (" + std::to_string(irradiance_.size()) + " points)" : std::string("off")) << "\n";
  }
  if (settings_.progressive) {
    s << "progressive: " << stats_.passes << " photon passes (maps above: the last; and " << stats_.pilot_passes
      << " for the pilot), alpha " << settings_.alpha
      << ", first radii " << global_r1_ << " (global), " << caustic_r1_ << " (caustic)\n";
    s << "photons emitted, all passes: " << stats_.global_emitted << " (global), " << stats_.caustic_emitted
      << " (caustic)\n";
  } else {
    s << "progressive: no\nphotons emitted: " << stats_.global_emitted << " (global), " << stats_.caustic_emitted
      << " (caustic)\n";
  }
  if (media_) {
    s << "participating media: the global map's estimate at surfaces, the beam radiance estimate along media\n";
    s << "volume map: " << stats_.volume_photons << " photons (last pass), first radius " << volume_r1_
      << ", now " << volume_radius() << "\n";
    s << "volume caustic map: " << stats_.volume_caustic_photons << " photons (last pass), first radius "
      << volume_caustic_r1_ << ", now " << volume_caustic_radius() << "; its paths (L S+ V) carry "
      << 100.0 * stats_.volume_caustic_share << " % of the global volume photons' flux\n";
    const size_t nv = stats_.volume_photons + stats_.volume_caustic_photons;
    if (nv > 0) s << "bytes per volume photon (records, kd-tree, hierarchy): " << double(stats_.volume_bytes) / double(nv) << "\n";
  }
  s << "max_depth: " << settings_.max_depth << "\n";
  s << "photon pass time: " << stats_.photon_seconds << " s\n";
  s << "kd-tree build time: " << stats_.build_seconds << " s\n";
  if (final_gather_) s << "irradiance precompute time: " << stats_.irradiance_seconds << " s\n";
  const size_t total = ng + nc;
  if (total > 0) {
    s << "bytes per photon (records + kd-tree): "
      << double(stats_.global_bytes + stats_.caustic_bytes) / double(total) << "\n";
  }
  return s.str();
}

}  // namespace caustica
