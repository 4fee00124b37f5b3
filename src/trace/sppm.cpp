// SPPM: visible points found by the render loop's camera samples, photons from the shared
// photon tracer, per-pixel statistics updated as pbrt-v3's SPPMIntegrator does.
#include "trace/sppm.h"
#include <algorithm>
#include <iostream>
#include <sstream>
#include "photon/gather.h"
#include "photon/photon_tracer.h"
#include "photon/volume_boundary.h"
#include "trace/eye_path.h"

namespace caustica {
namespace {
thread_local std::vector<Neighbour> tls_scratch;
}  // namespace

SppmSettings SppmSettings::read(const Params& p, const RenderSettings& render) {
  SppmSettings s;
  static_cast<MonteCarloSettings&>(s) = read_monte_carlo(p, render);
  s.photons = size_t(p.integer("photons", int64_t(s.photons), 1, int64_t(1) << 31));
  s.radius = float(p.number_in("radius", s.radius, 0.0, 1e30));
  s.alpha = float(p.number_in("alpha", s.alpha, 1e-3, 0.999));
  s.glossy_threshold = float(p.number_in("glossy_threshold", s.glossy_threshold, 0.0, 1e30));
  return s;
}

void SppmPixel::add_pass(size_t m, const Color& phi, float alpha, int dimensions) {
  if (m == 0) return;
  const double n_new = n + double(alpha) * double(m);
  const double ratio = n_new / (n + double(m));
  radius *= float(dimensions == 3 ? std::cbrt(ratio) : std::sqrt(ratio));
  tau = (tau + glm::dvec3(phi)) * (dimensions == 3 ? std::pow(ratio, 2.0 / 3.0) : ratio);
  n = n_new;
}

std::unique_ptr<Integrator> SppmIntegrator::create(const Params& p, const RenderSettings& render) {
  return std::make_unique<SppmIntegrator>(SppmSettings::read(p, render));
}

void SppmIntegrator::preprocess(const Scene& scene, const PreprocessContext&) {
  // (In media the volume map may hold up to kVolumeShare times the photons.)
  check_photon_memory(settings_.photons * (1 + (scene.has_media() ? PhotonPassSettings::kVolumeShare : 0)));
  const float area = std::max(scene.surface_area(), 1e-12f);
  radius0_ = settings_.radius > 0 ? settings_.radius
                                  : std::sqrt(50.0f * area / (kPi * float(std::max<size_t>(settings_.photons, 1))));
  SppmPixel first;
  first.radius = radius0_;
  pixels_.assign(size_t(scene.camera.width()) * size_t(scene.camera.height()), first);
  volume_pixels_.clear();  // (their first radius comes from the first pass's volume photons)
  volume_radius0_ = 0;
  passes_ = 0;
}

bool SppmIntegrator::begin_pass(const Scene& scene, int pass, const PreprocessContext& context) {
  PhotonPassSettings s;
  s.global_photons = settings_.photons;
  s.caustic_photons = 0;  // the global map holds the caustic paths too
  s.max_depth = settings_.max_depth;
  s.glossy_threshold = settings_.glossy_threshold;
  s.seed = pass == 0 ? context.seed : hash_seed(context.seed, uint64_t(pass), 0x7370706d);  // "sppm"
  s.cancel = context.cancel;
  PhotonPassResult r = trace_photons(scene, s);
  photon_seconds_ += r.seconds;
  emitted_ += r.global_emitted;
  report_new_warnings(r.warnings, warnings_, context.quiet);
  if (context.cancel && context.cancel->load()) return false;
  map_.build(std::move(r.global), r.global_scale);
  if (scene.has_media()) {
    volume_.build(std::move(r.volume), r.volume_scale);
    if (volume_pixels_.empty()) {
      // The balls' first radius: given, or holding 50 photons (the median over the first map),
      // or a two-hundredth of the scene's size where the map is (near) empty.
      volume_radius0_ = settings_.radius > 0 ? settings_.radius : volume_.median_knn_radius(50);
      if (!(volume_radius0_ > 0.0f)) volume_radius0_ = 0.005f * glm::length(scene.bounds().extent());
      SppmPixel first;
      first.radius = volume_radius0_;
      volume_pixels_.assign(pixels_.size(), first);
    }
  }
  ++passes_;
  return true;
}

Color SppmIntegrator::Li(const Ray& camera_ray, const Scene& scene, Sampler& sampler) const {
  const int max_depth = settings_.max_depth;
  // In media, as `path` (trace_volume_path): null boundaries are no vertices, and the
  // throughput is under spectral MIS over the path's medium events (EyePath::advance).
  const bool media = scene.has_media();
  EyePath path{Color(0.0f), Color(1.0f), BsdfVertex{}, max_depth, settings_.hide_emitters, media};
  Color& L = path.L;
  Color& beta = path.beta;
  if (media) path.hero = std::min(int(sampler.next1d() * 3.0f), 2);
  int32_t medium = scene.camera_medium;
  Ray ray = camera_ray;
  int depth = 0;
  for (int segment = 0; segment < 4 * (max_depth + 1) + 256; ++segment) {
    SurfaceHit hit;
    float t = 0.0f;
    const EyePath::Step step = path.advance(scene, ray, medium, depth, sampler, hit, t);
    if (step == EyePath::Step::kEnd) break;
    if (step == EyePath::Step::kScattered) {
      // The visible point in the medium: direct light by a shadow ray, the volume photons.
      if (depth >= max_depth) break;
      const Vec3 p = ray.at(t), wo = -ray.dir;
      L += path.throughput() * direct_in_medium_mis(scene, p, wo, medium, sampler);
      gather_volume(scene, p, wo, medium, depth, path.throughput(), sampler);
      break;
    }
    const Vec3 wo = -ray.dir;
    const Bsdf& m = *hit.material;
    if (is_gather_surface(m, settings_.glossy_threshold)) {
      // A coat (plastic's delta lobe) is not in the photon estimate: follow it instead of
      // stopping here, with probability in proportion to its weight (one listed lobe), or a
      // half (a delta continuation drawn from the BSDF: delta_continuation).
      BsdfSample coat[2];
      const bool listed = m.has(kBsdfSpecular) && m.specular_lobes(hit.frame.to_local(wo), coat, hit.sp) == 1;
      bool follow_coat = false;
      if (m.has(kBsdfSpecular) && (!listed || !is_black(coat[0].weight))) {
        const float p_coat = listed ? std::clamp(max_component(coat[0].weight), 0.1f, 0.9f) : 0.5f;
        follow_coat = sampler.next1d() < p_coat;
        if (follow_coat) {
          if (!listed && !delta_continuation(m, hit.frame.to_local(wo), hit.sp, [&] { return sampler.next1d(); }, coat[0]))
            break;
          const Vec3 wi = hit.frame.to_world(coat[0].wi);
          if (hit.leaks(wi)) break;
          beta *= radiance_weight(m, hit.frame.to_local(wo), coat[0], hit.sp) / p_coat;
          path.from = BsdfVertex{};
          ray = spawn_ray(hit.p, hit.n, wi);
          if (hit.media) medium = hit.media->entered(wi, hit.n);
        } else {
          beta /= 1.0f - p_coat;
        }
      }
      if (!follow_coat) {
        // The visible point: direct light by a shadow ray (no BSDF sample follows to share it),
        // and the pass's photons.
        L += path.throughput() * estimate_direct(scene, hit, wo, sampler, 0.0f, medium);
        gather_surface(hit, wo, depth, path.throughput(), sampler);
        break;
      }
    } else {
      if (!m.is_specular()) L += path.throughput() * estimate_direct(scene, hit, wo, sampler, 1.0f, medium);
      if (!path.scatter(hit, wo, sampler, ray)) break;
      if (hit.media) medium = hit.media->entered(ray.dir, hit.n);
      if (path.crossed_null) continue;  // (not a vertex, as for `path`)
    }
    ++depth;
  }
  return L;
}

void SppmIntegrator::gather_surface(const SurfaceHit& hit, const Vec3& wo, int depth, const Color& throughput,
                                    Sampler& sampler) const {
  // The photons of 1 .. max_depth - 1 - depth bounces within the pixel's radius (the 0-bounce
  // ones are the direct light).
  const int max_bounces = settings_.max_depth - 1 - depth;
  if (max_bounces < 1 || map_.empty()) return;
  if (sampler.pixel >= pixels_.size()) return;  // not a pixel of the film preprocess saw
  SppmPixel& px = pixels_[sampler.pixel];
  EstimateSettings est;
  est.fixed_radius = true;
  est.max_radius = px.radius;
  EstimateInfo info;
  const Color estimate = radiance_estimate(map_, hit, wo, with_bounces(est, 1, max_bounces), tls_scratch, &info);
  // radiance_estimate divides by the disc's area; the statistics keep the flux. A non-finite
  // estimate would stay in tau for good: it is dropped, as the render loop drops such samples.
  const Color phi = sampler.filter_weight * throughput * estimate * (kPi * px.radius * px.radius);
  if (is_finite(phi)) px.add_pass(info.photons, phi, settings_.alpha);
}

void SppmIntegrator::gather_volume(const Scene& scene, const Vec3& p, const Vec3& wo, int32_t medium, int depth,
                                   const Color& throughput, Sampler& sampler) const {
  const int max_bounces = settings_.max_depth - 1 - depth;
  if (max_bounces < 1 || volume_.empty()) return;
  if (sampler.pixel >= volume_pixels_.size()) return;
  SppmPixel& px = volume_pixels_[sampler.pixel];
  // This medium's photons of 1 .. max_bounces scattering events within the ball, each its flux
  // times the phase function over the ball's volume (Jensen and Christensen 1998): sigma_s
  // times the light scattered at p, which the throughput to p has the sigma_s of already.
  const Medium& med = *scene.media[size_t(medium)];
  const PhaseFunction& phase = med.phase();
  const Color sigma_s = med.sigma_s(p);
  std::vector<Neighbour>& found = tls_scratch;
  volume_.photons().radius_query(p, px.radius, found);
  Color sum(0.0f);
  size_t m = 0;
  for (const Neighbour& nb : found) {
    const Photon& ph = volume_.photons()[nb.index];
    if (ph.bounces < 1 || ph.bounces > max_bounces || photon_medium(ph) != medium) continue;
    sum += phase.eval(wo, ph.incoming_dir()) * ph.power();
    ++m;
  }
  const float r = px.radius;
  // The ball's volume in this medium and on p's side of surfaces, not the whole ball's: beside a
  // wall or the medium's bounds the photons fill only that part (the kernel renormalised at a
  // boundary, as `photon` does per photon; here per visible point, its radius being the pixel's).
  float fraction = 1.0f;
  if (m > 0) {
    uint64_t rays = 0;
    fraction = std::max(medium_ball_fraction(scene, p, medium, r, kBoundaryDirections, sampler.rng, rays),
                        1.0f / kMaxBoundaryWeight);
    sampler.rays += rays;
  }
  Color estimate = sum * volume_.photons().flux_scale() / (4.0f / 3.0f * kPi * r * r * r * fraction);
  for (int c = 0; c < 3; ++c) estimate[c] = sigma_s[c] > 0.0f ? estimate[c] / sigma_s[c] : 0.0f;
  const Color phi = sampler.filter_weight * throughput * estimate * (kPi * r * r);
  if (is_finite(phi)) px.add_pass(m, phi, settings_.alpha, 3);
}

void SppmIntegrator::resolve(Image& mean, const std::vector<int>& pixel_passes) const {
  // In media, the passes whose visible point lay in a medium add theirs alike (the ball's
  // estimate was kept as radiance times pi r^2); both are averaged over all the pixel's passes.
  for (const std::vector<SppmPixel>* stats : {&pixels_, &volume_pixels_}) {
    for (size_t i = 0; i < stats->size() && i < mean.pixels.size(); ++i) {
      const SppmPixel& px = (*stats)[i];
      if (pixel_passes[i] <= 0 || px.radius <= 0) continue;
      const double area = double(kPi) * double(px.radius) * double(px.radius);
      mean.pixels[i] += Color(px.tau / (double(pixel_passes[i]) * area));
    }
  }
}

std::string SppmIntegrator::describe() const {
  std::ostringstream s;
  double r_sum = 0;
  for (const SppmPixel& px : pixels_) r_sum += px.radius;
  s << "photons per pass: " << settings_.photons << "\n";
  s << "passes: " << passes_ << " (" << emitted_ << " photons emitted)\n";
  s << "alpha: " << settings_.alpha << "\n";
  s << "radius: " << radius0_ << " first, " << (pixels_.empty() ? 0.0 : r_sum / double(pixels_.size()))
    << " mean now\n";
  if (!volume_pixels_.empty()) {
    double v_sum = 0;
    for (const SppmPixel& px : volume_pixels_) v_sum += px.radius;
    s << "volume radius: " << volume_radius0_ << " first, " << v_sum / double(volume_pixels_.size()) << " mean now\n";
  }
  s << "max_depth: " << settings_.max_depth << "\n";
  s << "photon pass time: " << photon_seconds_ << " s\n";
  return s.str();
}

}  // namespace caustica
