#include "core/media/homogeneous.h"
#include <algorithm>
#include <cmath>

namespace caustica {

Color beer_lambert(const Color& sigma_t, float d) {
  Color tr;
  for (int c = 0; c < 3; ++c) tr[c] = sigma_t[c] > 0.0f ? std::exp(-sigma_t[c] * d) : 1.0f;
  return tr;
}

HomogeneousMedium::HomogeneousMedium(const Color& sigma_t, const Color& albedo, std::unique_ptr<PhaseFunction> phase)
    : sigma_t_(sigma_t), sigma_s_(sigma_t * albedo), phase_(std::move(phase)) {}

MediumEvent HomogeneousMedium::sample(const Ray&, float tmax, int channel, Sampler& sampler, FlightRecord* record) const {
  if (record) record->clear();  // (no null collisions)
  MediumEvent e;
  e.t = tmax;
  // Nothing scatters: the segment passes, its transmittance the weight (for every channel).
  if (is_black(sigma_s_)) {
    e.weight = beer_lambert(sigma_t_, tmax);
    return e;
  }
  const float s = sigma_t_[channel];
  const float t = s > 0.0f ? -std::log1p(-sampler.next1d()) / s : kInfinity;
  if (t < tmax) {
    const Color tr = beer_lambert(sigma_t_, t);
    e.scattered = true;
    e.t = t;
    e.weight = sigma_s_ * tr;
    e.pdf = sigma_t_ * tr;
    return e;
  }
  e.weight = e.pdf = beer_lambert(sigma_t_, tmax);
  return e;
}

Color HomogeneousMedium::transmittance(const Ray&, float tmax, Sampler&) const { return beer_lambert(sigma_t_, tmax); }

std::unique_ptr<Medium> HomogeneousMedium::create(const Params& p) {
  const bool by_t = p.has("sigma_t") || p.has("albedo");
  const bool by_as = p.has("sigma_a") || p.has("sigma_s");
  if (by_t && by_as) p.fail("", "give sigma_t and albedo (Mitsuba's), or sigma_a and sigma_s (pbrt's), not both pairs");
  const double scale = p.number("scale", 1.0);
  if (!(scale >= 0.0)) p.fail("scale", "scale must not be negative");
  Color sigma_t, albedo;
  if (by_as) {
    const Color a = p.color("sigma_a", Color(0.0f)), s = p.color("sigma_s", Color(0.0f));
    sigma_t = a + s;
    for (int c = 0; c < 3; ++c) albedo[c] = sigma_t[c] > 0.0f ? s[c] / sigma_t[c] : 0.0f;
  } else {
    // Mitsuba's defaults: sigma_t 1, albedo 0.75.
    sigma_t = p.color("sigma_t", Color(1.0f));
    albedo = p.color("albedo", Color(0.75f));
    if (max_component(albedo) > 1.0f) p.fail("albedo", "albedo must lie in [0, 1] (above 1 the medium would create light)");
  }
  sigma_t *= float(scale);
  if (!std::isfinite(max_component(sigma_t))) p.fail("scale", "sigma_t times scale overflows");
  return std::make_unique<HomogeneousMedium>(sigma_t, albedo, p.phase("phase"));
}

}  // namespace caustica
