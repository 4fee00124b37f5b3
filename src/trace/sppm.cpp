// SPPM: visible points found by the render loop's camera samples, photons from the shared
// photon tracer, per-pixel statistics updated as pbrt-v3's SPPMIntegrator does.
#include "trace/sppm.h"
#include <algorithm>
#include <iostream>
#include <sstream>
#include "photon/gather.h"
#include "photon/photon_tracer.h"
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

void SppmPixel::add_pass(size_t m, const Color& phi, float alpha) {
  if (m == 0) return;
  const double n_new = n + double(alpha) * double(m);
  const double shrink2 = n_new / (n + double(m));
  radius *= float(std::sqrt(shrink2));
  tau = (tau + glm::dvec3(phi)) * shrink2;
  n = n_new;
}

std::unique_ptr<Integrator> SppmIntegrator::create(const Params& p, const RenderSettings& render) {
  return std::make_unique<SppmIntegrator>(SppmSettings::read(p, render));
}

void SppmIntegrator::preprocess(const Scene& scene, const PreprocessContext&) {
  check_photon_memory(settings_.photons);
  const float area = std::max(scene.surface_area(), 1e-12f);
  radius0_ = settings_.radius > 0 ? settings_.radius
                                  : std::sqrt(50.0f * area / (kPi * float(std::max<size_t>(settings_.photons, 1))));
  SppmPixel first;
  first.radius = radius0_;
  pixels_.assign(size_t(scene.camera.width()) * size_t(scene.camera.height()), first);
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
  ++passes_;
  return true;
}

Color SppmIntegrator::Li(const Ray& camera_ray, const Scene& scene, Sampler& sampler) const {
  const int max_depth = settings_.max_depth;
  EyePath path{Color(0.0f), Color(1.0f), BsdfVertex{}, max_depth, settings_.hide_emitters};
  Ray ray = camera_ray;
  for (int depth = 0;; ++depth) {
    SurfaceHit hit;
    if (!path.meet(scene, ray, depth, sampler, hit)) break;
    const Vec3 wo = -ray.dir;
    const Bsdf& m = *hit.material;
    if (!is_gather_surface(m, settings_.glossy_threshold)) {
      if (!m.is_specular()) path.L += path.beta * estimate_direct(scene, hit, wo, sampler, 1.0f);
      if (!path.scatter(hit, wo, sampler, ray)) break;
      continue;
    }
    // A coat (plastic's delta lobe) is not in the photon estimate: follow it instead of
    // stopping here, with probability in proportion to its weight (one listed lobe), or a half
    // (a delta continuation drawn from the BSDF: delta_continuation).
    BsdfSample coat[2];
    const bool listed = m.has(kBsdfSpecular) && m.specular_lobes(hit.frame.to_local(wo), coat, hit.sp) == 1;
    if (m.has(kBsdfSpecular) && (!listed || !is_black(coat[0].weight))) {
      const float p_coat = listed ? std::clamp(max_component(coat[0].weight), 0.1f, 0.9f) : 0.5f;
      if (sampler.next1d() < p_coat) {
        if (!listed && !delta_continuation(m, hit.frame.to_local(wo), hit.sp, [&] { return sampler.next1d(); }, coat[0]))
          break;
        const Vec3 wi = hit.frame.to_world(coat[0].wi);
        if (hit.leaks(wi)) break;
        path.beta *= radiance_weight(m, hit.frame.to_local(wo), coat[0], hit.sp) / p_coat;
        path.from = BsdfVertex{};
        ray = spawn_ray(hit.p, hit.n, wi);
        continue;
      }
      path.beta /= 1.0f - p_coat;
    }
    // The visible point: direct light by a shadow ray (no BSDF sample follows to share it),
    // and the pass's photons of 1 .. max_depth - 1 - depth bounces within the pixel's radius
    // (the 0-bounce ones are the direct light).
    path.L += path.beta * estimate_direct(scene, hit, wo, sampler, 0.0f);
    if (max_depth - 1 - depth < 1 || map_.empty()) break;
    if (sampler.pixel >= pixels_.size()) break;  // not a pixel of the film preprocess saw
    SppmPixel& px = pixels_[sampler.pixel];
    EstimateSettings est;
    est.fixed_radius = true;
    est.max_radius = px.radius;
    EstimateInfo info;
    const Color estimate = radiance_estimate(map_, hit, wo, with_bounces(est, 1, max_depth - 1 - depth), tls_scratch, &info);
    // radiance_estimate divides by the disc's area; the statistics keep the flux. A non-finite
    // estimate would stay in tau for good: it is dropped, as the render loop drops such samples.
    const Color phi = sampler.filter_weight * path.beta * estimate * (kPi * px.radius * px.radius);
    if (is_finite(phi)) px.add_pass(info.photons, phi, settings_.alpha);
    break;
  }
  return path.L;
}

void SppmIntegrator::resolve(Image& mean, const std::vector<int>& pixel_passes) const {
  for (size_t i = 0; i < pixels_.size() && i < mean.pixels.size(); ++i) {
    const SppmPixel& px = pixels_[i];
    if (pixel_passes[i] <= 0 || px.radius <= 0) continue;
    const double area = double(kPi) * double(px.radius) * double(px.radius);
    mean.pixels[i] += Color(px.tau / (double(pixel_passes[i]) * area));
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
  s << "max_depth: " << settings_.max_depth << "\n";
  s << "photon pass time: " << photon_seconds_ << " s\n";
  return s.str();
}

}  // namespace caustica
