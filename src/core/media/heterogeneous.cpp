#include "core/media/heterogeneous.h"
#include <algorithm>
#include <cmath>

namespace caustica {

HeterogeneousMedium::HeterogeneousMedium(std::unique_ptr<Volume> sigma_t, std::unique_ptr<Volume> albedo, float scale,
                                         std::unique_ptr<PhaseFunction> phase)
    : sigma_t_(std::move(sigma_t)),
      albedo_(std::move(albedo)),
      scale_(scale),
      majorant_(sigma_t_->max_value() * scale),
      phase_(std::move(phase)) {}

namespace {
// 1 in each channel without extinction, 0 in the others.
Color no_extinction(const Color& sigma) {
  return Color(sigma.x > 0.0f ? 0.0f : 1.0f, sigma.y > 0.0f ? 0.0f : 1.0f, sigma.z > 0.0f ? 0.0f : 1.0f);
}
}  // namespace

Color HeterogeneousMedium::sigma_s(const Vec3& p) const { return sigma_t_->eval(p) * scale_ * albedo_->eval(p); }

bool HeterogeneousMedium::clip(const Ray& ray, float tmax, float& t0, float& t1) const {
  t0 = 0.0f;
  t1 = tmax;
  const Bounds b = sigma_t_->bounds();
  if (b.empty()) return majorant_ > 0.0f;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / ray.dir[a];
    float near = (b.lo[a] - ray.origin[a]) * inv, far = (b.hi[a] - ray.origin[a]) * inv;
    if (near > far) std::swap(near, far);
    // (A direction along the slab: inv is infinite, and a NaN from 0 * inf keeps the bound.)
    if (near > t0) t0 = near;
    if (far < t1) t1 = far;
  }
  return t0 < t1 && majorant_ > 0.0f;
}

MediumEvent HeterogeneousMedium::sample(const Ray& ray, float tmax, int channel, Sampler& sampler,
                                        FlightRecord* record) const {
  if (record) record->clear();
  MediumEvent e;
  e.t = tmax;
  float t0, t1;
  if (!clip(ray, tmax, t0, t1)) return e;
  // An unbounded constant volume along a ray to infinity, a channel of no extinction tracked:
  // no collision ever comes. Each channel's chance of none is 1 where it has no extinction, 0
  // where it has some (the products of null collisions' chances to infinity).
  const bool chromatic = sigma_t_->channels() != 1;
  if (chromatic && !std::isfinite(t1)) {
    const Color sigma = sigma_t_->eval(ray.origin);
    if (!(sigma[channel] > 0.0f)) {
      e.weight = e.pdf = no_extinction(sigma);
      return e;
    }
  }
  // Delta tracking: tentative collisions at the majorant's rate, each real with probability
  // sigma_t / majorant in the hero channel; a real one scatters with the albedo as weight
  // (absorption ends the path in expectation). With one channel of extinction every channel's
  // density is the same (pdf 1). With a chromatic one, each channel's density of the same
  // decisions is the product of its chances of them (1 - sigma_c / majorant at each null
  // collision, sigma_c / majorant at the real one; the majorant's exponentials are shared and
  // cancel), and the weight that product times the albedo (spectral MIS over the path).
  Color nulls(1.0f);  // per channel, the product of the null collisions' chances
  for (float t = t0;;) {
    t -= std::log1p(-sampler.next1d()) / majorant_;
    if (!(t < t1)) {
      if (chromatic) e.weight = e.pdf = nulls;
      return e;
    }
    const Vec3 p = ray.at(t);
    const Color sigma = sigma_t_->eval(p) * scale_;
    if (sampler.next1d() * majorant_ < (chromatic ? sigma[channel] : sigma.x)) {
      e.scattered = true;
      e.t = t;
      e.weight = albedo_->eval(p);
      if (chromatic) {
        e.pdf = nulls * sigma / majorant_;
        e.weight *= e.pdf;
      }
      return e;
    }
    if (chromatic) {
      nulls *= Color(1.0f) - sigma / majorant_;
      if (record && average(nulls) > 0.0f) {
        record->t.push_back(t);
        record->ratio.push_back(nulls / average(nulls));
      }
      // Weight and densities may share any factor: rescale before a long walk underflows them.
      const float m = max_component(nulls);
      if (m < 1e-20f && m > 0.0f) nulls /= m;
    }
  }
}

Color HeterogeneousMedium::transmittance(const Ray& ray, float tmax, Sampler& sampler) const {
  float t0, t1;
  if (!clip(ray, tmax, t0, t1)) return Color(1.0f);
  // An unbounded constant volume to infinity: a channel with extinction keeps nothing, one
  // without keeps all (ratio tracking would never end).
  if (!std::isfinite(t1)) return no_extinction(sigma_t_->eval(ray.origin));
  // Ratio tracking: per channel, the product of each tentative collision's chance of being a
  // null one.
  Color tr(1.0f);
  for (float t = t0;;) {
    t -= std::log1p(-sampler.next1d()) / majorant_;
    if (!(t < t1)) return tr;
    tr *= Color(1.0f) - sigma_t_->eval(ray.at(t)) * (scale_ / majorant_);
    // Russian roulette once little is left (unbiased: the survivors carry twice as much).
    if (max_component(tr) < 0.05f) {
      if (sampler.next1d() < 0.5f) return Color(0.0f);
      tr *= 2.0f;
    }
  }
}

std::unique_ptr<Medium> HeterogeneousMedium::create(const Params& p) {
  const double scale = p.number("scale", 1.0);
  if (!(scale >= 0.0)) p.fail("scale", "scale must not be negative");
  std::unique_ptr<Volume> sigma_t = p.volume("sigma_t", Color(1.0f));
  std::unique_ptr<Volume> albedo = p.volume("albedo", Color(0.75f));
  if (albedo->max_value() > 1.0f) p.fail("albedo", "albedo must lie in [0, 1] (above 1 the medium would create light)");
  if (!std::isfinite(sigma_t->max_value() * scale)) p.fail("scale", "sigma_t times scale overflows");
  return std::make_unique<HeterogeneousMedium>(std::move(sigma_t), std::move(albedo), float(scale), p.phase("phase"));
}

}  // namespace caustica
