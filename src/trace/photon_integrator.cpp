// Photon mapping eye pass: at the first diffuse hit, direct light by shadow rays, caustics
// from the caustic map, indirect light by final gathering into the global map (Jensen 1996).
#include "trace/photon_integrator.h"
#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <tbb/parallel_invoke.h>
#include "photon/gather.h"
#include "photon/photon_tracer.h"
#include "trace/eye_path.h"

namespace caustica {
namespace {
thread_local std::vector<Neighbour> tls_scratch;
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
  integer("irradiance_stride", s.irradiance_stride, 0, 1 << 20);
  number("glossy_threshold", s.glossy_threshold);
  number("caustic_threshold", s.caustic_threshold);
  s.alpha = float(p.number_in("alpha", s.alpha, 1e-3, 0.999));
  return s;
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
  const size_t for_image = PhotonSettings::photons_for_image(scene.camera.width(), scene.camera.height());
  if (settings_.photons_from_image) settings_.photons = for_image;
  if (settings_.caustic_photons_from_image) settings_.caustic_photons = for_image;
  check_photon_memory(settings_.photons + (final_gather_ ? settings_.caustic_photons : 0));
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
    global_r1_ = settings_.global_radius > 0 ? settings_.global_radius
                                             : 3.0f * even_radius(settings_.global_k, settings_.photons);
    caustic_r1_ = settings_.caustic_radius > 0 ? settings_.caustic_radius
                                               : even_radius(settings_.caustic_k, settings_.caustic_photons);
    // The first pass's maps now (so that `caustica photons` and the AOVs see maps); the others
    // in begin_pass.
    built_pass_ = -1;
    begin_pass(scene, context.first_pass, context);
    return;
  }
  if (!build_maps(scene, context.seed, context)) return;
  global_est_.max_radius = settings_.global_radius > 0 ? settings_.global_radius
                                                       : 3.0f * even_radius(settings_.global_k, global_.size());
  caustic_est_.max_radius = settings_.caustic_radius > 0 ? settings_.caustic_radius
                                                         : even_radius(settings_.caustic_k, caustic_.size());
  build_irradiance();
}

bool PhotonIntegrator::begin_pass(const Scene& scene, int pass, const PreprocessContext& context) {
  if (!settings_.progressive || pass == built_pass_) return true;
  // Each estimate's disc (the k nearest photons', at most the first radii) shrinks by the
  // schedule: per pass the same adaptive disc as without progression, scaled.
  const float scale2 = float(progressive_radius2_scale(pass, settings_.alpha));
  global_est_.max_radius = global_r1_;
  caustic_est_.max_radius = caustic_r1_;
  global_est_.radius2_scale = caustic_est_.radius2_scale = scale2;
  // Pass i's photons come from their own seed: the image is the same for any thread count.
  const uint64_t seed = pass == 0 ? context.seed : hash_seed(context.seed, uint64_t(pass), 0x70706d);  // "ppm"
  if (!build_maps(scene, seed, context)) return false;
  build_irradiance();
  built_pass_ = pass;
  return true;
}

void PhotonIntegrator::build_irradiance() {
  irradiance_ = IrradianceCache{};  // never a previous pass's
  if (!final_gather_ || settings_.irradiance_stride <= 0 || global_.empty()) return;
  const auto t0 = std::chrono::steady_clock::now();
  // For the gathers' points at eye vertices 1 .. 8 (gathers from eye vertices 0 .. 7).
  irradiance_.build(global_, size_t(settings_.irradiance_stride), at_depth(global_est_, 1), 8);
  stats_.irradiance_seconds += seconds_since(t0);
  stats_.irradiance_bytes = irradiance_.memory_bytes();
}

bool PhotonIntegrator::build_maps(const Scene& scene, uint64_t seed, const PreprocessContext& context) {
  PhotonPassSettings pass;
  pass.global_photons = settings_.photons;
  pass.caustic_photons = final_gather_ ? settings_.caustic_photons : 0;
  pass.max_depth = settings_.max_depth;
  pass.glossy_threshold = settings_.glossy_threshold;
  pass.caustic_threshold = final_gather_ ? settings_.caustic_threshold : pass.caustic_threshold;
  pass.seed = seed;
  pass.cancel = context.cancel;
  PhotonPassResult r = trace_photons(scene, pass);
  stats_.photon_seconds += r.seconds;
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
    if (irradiance_.lookup(hit.p, n_side, est.max_radius * std::sqrt(est.radius2_scale), level, E, scratch)) return hit.material->albedo(hit.sp) * kInvPi * E;
  }
  return radiance_estimate(global_, hit, wo, est, scratch);
}

Color PhotonIntegrator::final_gather(const Scene& scene, const SurfaceHit& hit, const Vec3& wo, Sampler& sampler,
                                     std::vector<Neighbour>& scratch, bool skip_delta, int eye_depth) const {
  const int n = settings_.gather_rays;
  if (n <= 0) return Color(0.0f);
  const Vec3 wo_l = hit.frame.to_local(wo);
  // Stratified over an sx x sy grid; the remainder unstratified.
  const int sx = std::max(1, int(std::sqrt(float(n)))), sy = n / sx;
  Color sum(0.0f);
  for (int i = 0; i < n; ++i) {
    Vec2 u = sampler.next2d();
    if (i < sx * sy) u = Vec2((float(i % sx) + u.x) / float(sx), (float(i / sx) + u.y) / float(sy));
    BsdfSample bs;
    if (!hit.material->sample(wo_l, u, sampler.next1d(), bs, hit.sp)) continue;
    if (skip_delta && bs.delta) continue;  // the caller traces the delta lobes
    const Vec3 wi = hit.frame.to_world(bs.wi);
    if (hit.leaks(wi)) continue;
    Color throughput = bs.weight;
    Ray ray = spawn_ray(hit.p, hit.n, wi);
    BsdfVertex from{bs.delta, gather_ratio() * bs.pdf, hit.p};
    // The emission a segment reaches is the gather's when the segment starts at the gather
    // point (direct light, shared with the shadow rays by MIS) or when a soft surface lies
    // between; through caustic surfaces alone it is the caustic map's.
    bool counts_emission = true, past_soft = false;
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
      if (is_gather_surface(m, settings_.glossy_threshold)) {
        sum += throughput * indirect_at(g, -ray.dir, scratch, eye_depth + 1 + depth);
        // The photon estimate has no delta part: a coat (plastic) passes the gather ray on, as
        // the caustic map's photons pass through it; the emission it reaches is the caustic map's.
        BsdfSample coat[2];
        if (!m.has(kBsdfSpecular) || m.specular_lobes(g.frame.to_local(-ray.dir), coat, g.sp) != 1) break;
        const Vec3 cwi = g.frame.to_world(coat[0].wi);
        if (g.leaks(cwi)) break;
        throughput *= coat[0].weight;
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
      if (!m.sample(g.frame.to_local(gwo), us, sampler.next1d(), ss, g.sp)) break;
      const Vec3 gwi = g.frame.to_world(ss.wi);
      if (g.leaks(gwi)) break;
      throughput *= ss.weight;
      from = BsdfVertex{ss.delta, ss.pdf, g.p};
      counts_emission = past_soft;
      ray = spawn_ray(g.p, g.n, gwi);
    }
  }
  return sum / float(n);
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
  return trace_eye(camera_ray, scene, sampler, 0, kSplitLevels);
}

Color PhotonIntegrator::trace_eye(const Ray& start, const Scene& scene, Sampler& sampler, int depth,
                                  int splits_left) const {
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
      Color direct(0.0f);
      const float ratio = gather_ratio();
      for (int i = 0; i < settings_.direct_samples; ++i) direct += estimate_direct(scene, hit, wo, sampler, ratio);
      L += beta * direct / float(settings_.direct_samples);
      if (!caustic_.empty()) L += beta * radiance_estimate(caustic_, hit, wo, at_depth(caustic_est_, depth), scratch);
      // A delta lobe beside the diffuse one (plastic's coat): traced as the eye path goes on,
      // while the final gather covers the other lobes only. Without splits left, the gather's
      // delta samples carry it instead.
      const bool trace_coat = splits_left > 0 && m.has(kBsdfSpecular);
      L += beta * final_gather(scene, hit, wo, sampler, scratch, trace_coat, depth);
      if (trace_coat) {
        BsdfSample coat[2];
        const int n = m.specular_lobes(wo_l, coat, hit.sp);
        for (int i = 0; i < n; ++i) {
          const Vec3 wi = hit.frame.to_world(coat[i].wi);
          if (is_black(coat[i].weight) || hit.leaks(wi)) continue;
          L += beta * coat[i].weight * trace_eye(spawn_ray(hit.p, hit.n, wi), scene, sampler, depth + 1, splits_left - 1);
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
      for (const BsdfSample& lobe : lobes) {
        if (is_black(lobe.weight)) continue;
        const Ray next = spawn_ray(hit.p, hit.n, hit.frame.to_world(lobe.wi));
        split += lobe.weight * trace_eye(next, scene, sampler, depth + 1, splits_left - 1);
      }
      return L + beta * split;
    }
    // A glossy lobe below the gather threshold: direct light by a shadow ray, MIS-weighted
    // against the BSDF sample that continues the path.
    if (!m.is_specular()) L += beta * estimate_direct(scene, hit, wo, sampler, 1.0f);
    if (!path.scatter(hit, wo, sampler, ray)) break;
  }
  return L;
}

std::string PhotonIntegrator::describe() const {
  std::ostringstream s;
  const size_t ng = global_.size(), nc = caustic_.size();
  s << "photons (global, wanted): " << settings_.photons << "\n";
  if (final_gather_) s << "caustic photons (wanted): " << settings_.caustic_photons << "\n";
  s << "global map: " << ng << " stored, k " << global_est_.k << ", max radius " << global_est_.max_radius << "\n";
  if (final_gather_) {
    s << "caustic map: " << nc << " stored, k " << caustic_est_.k << ", max radius " << caustic_est_.max_radius << ", cone filter k " << caustic_est_.cone_k << "\n";
    s << "gather rays: " << settings_.gather_rays << "\ndirect samples: " << settings_.direct_samples << "\n";
    s << "precomputed irradiance: " << (settings_.irradiance_stride > 0 ? "every " + std::to_string(settings_.irradiance_stride) + "th global photon (" + std::to_string(irradiance_.size()) + " points)" : std::string("off")) << "\n";
  }
  if (settings_.progressive) {
    s << "progressive: " << stats_.passes << " photon passes (maps above: the last), alpha " << settings_.alpha
      << ", first radii " << global_r1_ << " (global), " << caustic_r1_ << " (caustic)\n";
    s << "photons emitted, all passes: " << stats_.global_emitted << " (global), " << stats_.caustic_emitted
      << " (caustic)\n";
  } else {
    s << "progressive: no\nphotons emitted: " << stats_.global_emitted << " (global), " << stats_.caustic_emitted
      << " (caustic)\n";
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
