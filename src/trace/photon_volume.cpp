// `photon` in participating media: the eye path's segments through media gather the volume
// photon maps by the beam radiance estimate (Jarosz, Zwicker and Jensen 2008), one radius for
// every photon, shrinking pass by pass as progressive photon mapping's (Jarosz et al. 2011 show
// the beam estimate converges so); single scattering is a shadow ray from one point of the
// segment, surfaces as in the global map's estimate mode (shadow rays, the global map).
// photon-direct: single scattering and the surfaces' direct light from the maps too.
#include "core/media/homogeneous.h"
#include "photon/gather.h"
#include "trace/eye_path.h"
#include "trace/photon_integrator.h"

namespace caustica {
namespace {
thread_local std::vector<Neighbour> tls_media_scratch;
thread_local FlightRecord tls_flight;
}  // namespace

template <class W>
Color PhotonIntegrator::beam_estimate(const Ray& ray, float tmax, float segment_end, bool open_start,
                                      const Scene& scene, int32_t medium, int depth, W&& weight) const {
  // (photon-direct: the photons straight from a light too, in place of single scattering.)
  const int min_bounces = final_gather_ ? 1 : 0;
  const int max_bounces = settings_.max_depth - 1 - depth;
  if (max_bounces < min_bounces) return Color(0.0f);
  const Vec3 wo = -ray.dir;
  const PhaseFunction& phase = scene.media[size_t(medium)]->phase();
  Color sum(0.0f);
  // Each photon's flux spread over the ball of its radius (a constant kernel, normalised over
  // the part of the ball in its medium: correct_volume_boundaries), taken along the ray within
  // the segment: L = sum p(wo, wi_p) Phi_p Tr(t_p) |chord_p cut to [0, segment_end]| / (4/3 pi r^3).
  auto gather = [&](const VolumePhotonMap& map, float radius, bool skip_caustic_paths) {
    if (map.empty() || !(radius > 0.0f)) return;
    Color part(0.0f);
    const float r2 = radius * radius;
    map.along(ray, open_start ? -radius : 0.0f, tmax, radius, [&](uint32_t i, float t, float d2) {
      const Photon& p = map.photons()[i];
      // (Only this medium's photons: a neighbouring medium's, or one behind a wall, lie within
      // the radius too.)
      if (p.bounces < min_bounces || p.bounces > max_bounces || photon_medium(p) != medium) return;
      if (skip_caustic_paths && is_caustic_path(p)) return;
      const float half = std::sqrt(std::max(0.0f, r2 - d2));
      const float chord = std::min(t + half, segment_end) - std::max(t - half, 0.0f);
      if (!(chord > 0.0f)) return;
      part += phase.eval(wo, p.incoming_dir()) * p.power() * (weight(std::max(t, 0.0f)) * chord);
    });
    sum += part * map.photons().flux_scale() / (4.0f / 3.0f * kPi * r2 * radius);
  };
  gather(volume_, volume_radius(), !volume_caustic_.empty() && volume_caustic_radius() > 0.0f);
  gather(volume_caustic_, volume_caustic_radius(), false);
  return sum;
}

Color PhotonIntegrator::trace_media_eye(const Ray& camera_ray, const Scene& scene, Sampler& sampler) const {
  std::vector<Neighbour>& scratch = tls_media_scratch;
  EyePath path{Color(0.0f), Color(1.0f), BsdfVertex{}, settings_.max_depth, settings_.hide_emitters, true};
  Color& L = path.L;
  Color& beta = path.beta;
  int32_t medium = scene.camera_medium;
  Ray ray = camera_ray;
  int depth = 0;
  for (int segment = 0; segment < 4 * (settings_.max_depth + 1) + 256; ++segment) {
    SurfaceHit hit;
    ++sampler.rays;
    const bool found = scene.intersect(ray, hit);
    const float s = found ? hit.t : kInfinity;
    if (medium >= 0) {
      const Medium& med = *scene.media[size_t(medium)];
      const Vec3 wo = -ray.dir;
      if (sampler.aov) sampler.aov[3] = volume_radius();  // (--aov: the volume estimate's radius)
      Color sigma_t, sigma_s;
      if (med.homogeneous(sigma_t, sigma_s)) {
        // Transmittance in closed form: the photons weighted by it, the segment's end reached
        // with it, single scattering from a point sampled equiangularly towards a light's.
        if (!is_black(sigma_s)) {
          L += beta * beam_estimate(ray, s, s, segment == 0, scene, medium, depth, [&](float t) { return beer_lambert(sigma_t, t); });
          if (depth < settings_.max_depth && final_gather_) {
            const Light* end_light = found && hit.light >= 0 ? scene.lights[size_t(hit.light)].get() : nullptr;
            L += beta * single_scattering(scene, ray, s, medium, sigma_t, sigma_s, sampler, end_light);
          }
        }
        beta *= beer_lambert(sigma_t, s);  // (0 past an infinite segment where sigma_t > 0)
        if (is_black(beta)) break;
      } else {
        // Free flight by delta tracking: whether the segment passes a point t is an unbiased
        // estimate of the hero channel's transmittance to it, so the photons before the flight's
        // end count in full where the extinction is grey, and where it is chromatic times the
        // MIS weights of the null collisions before them (FlightRecord); where the flight ends
        // the path scatters, a shadow ray there.
        const int hero = std::min(int(sampler.next1d() * 3.0f), 2);
        FlightRecord& flight = tls_flight;
        const MediumEvent event = med.sample(ray, s, hero, sampler, &flight);
        const float end = event.scattered ? event.t : s;
        if (flight.t.empty())
          L += beta * beam_estimate(ray, end, s, segment == 0, scene, medium, depth, [](float) { return 1.0f; });
        else
          L += beta * beam_estimate(ray, end, s, segment == 0, scene, medium, depth, [&](float t) { return flight.at(t); });
        // (The hero is chosen afresh for each flight: one-sample MIS over the channels, the
        // weight over the mean of the densities, as the flight record's.)
        const float pdf = event.flight_pdf(hero);
        if (!(pdf > 0.0f)) break;
        if (event.scattered) {
          if (depth < settings_.max_depth && final_gather_)
            L += beta * event.weight / pdf * direct_in_medium_mis(scene, ray.at(event.t), wo, medium, sampler);
          break;
        }
        beta *= event.weight / pdf;
        if (is_black(beta)) break;
      }
    }
    const bool visible = !(settings_.hide_emitters && depth == 0);
    if (!found) {
      if (visible) L += beta * escaped_mis(scene, ray.dir, path.from);
      break;
    }
    if (Scene::is_medium_boundary(hit)) {  // not a vertex: the ray goes on in the other medium
      Scene::cross(hit, ray, medium);
      continue;
    }
    if (visible) L += beta * emission_mis(scene, hit, scene.emitted(hit, hit.frame.to_local(-ray.dir)), path.from);
    if (depth >= settings_.max_depth) break;
    const Vec3 wo = -ray.dir;
    const Bsdf& m = *hit.material;
    if (is_gather_surface(m, settings_.glossy_threshold)) {
      if (sampler.aov) {
        EstimateInfo g;
        radiance_estimate(global_, hit, wo, global_est_, scratch, &g);
        sampler.aov[0] = float(g.photons);
        sampler.aov[2] = g.radius;
        sampler.aov[3] = volume_radius();  // (no surface caustic map in media)
      }
      // Direct light by shadow rays through the media, the rest from the global map (its
      // photons of one bounce or more, caustics included); photon-direct: all from the map.
      if (!final_gather_) {
        L += beta * radiance_estimate(global_, hit, wo, at_depth(global_est_, depth), scratch);
        break;
      }
      const int nd = settings_.direct_samples;
      const StratifiedDirect lights(sampler, nd);
      Color direct(0.0f);
      for (int i = 0; i < nd; ++i) direct += lights.estimate(scene, hit, wo, sampler, i, 0.0f, medium);
      L += beta * direct / float(nd);
      const EstimateSettings est = at_depth(global_est_, depth);
      if (est.max_bounces >= 1) L += beta * radiance_estimate(global_, hit, wo, with_bounces(est, 1, est.max_bounces), scratch);
      // A delta lobe beside the estimate's (plastic's coat) carries the path on.
      BsdfSample coat;
      const Vec3 wo_l = hit.frame.to_local(wo);
      if (!m.has(kBsdfSpecular) || !delta_continuation(m, wo_l, hit.sp, [&] { return sampler.next1d(); }, coat)) break;
      const Vec3 wi = hit.frame.to_world(coat.wi);
      if (hit.leaks(wi)) break;
      beta *= radiance_weight(m, wo_l, coat, hit.sp);
      path.from = BsdfVertex{};
      path.crossed_null = false;
      ray = spawn_ray(hit.p, hit.n, wi);
    } else {
      // Specular and smooth glossy surfaces: traced, a shadow ray at a glossy one (MIS against
      // the BSDF sample that goes on).
      if (!m.is_specular()) L += beta * estimate_direct(scene, hit, wo, sampler, 1.0f, medium);
      if (!path.scatter(hit, wo, sampler, ray)) break;
    }
    if (hit.media) medium = hit.media->entered(ray.dir, hit.n);
    if (path.crossed_null) continue;  // (not a vertex, as for `path`)
    ++depth;
    if (is_black(beta)) break;
  }
  return L;
}

}  // namespace caustica
