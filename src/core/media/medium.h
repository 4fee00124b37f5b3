// Participating media: what fills the space between surfaces (fog, smoke, murky water).
// A ray's segment through a medium either passes (transmittance) or scatters at a distance
// sampled along it (free-flight sampling); a scattering point takes the medium's phase
// function as a surface takes its BSDF. Colours are RGB: a chromatic extinction is sampled by
// one channel (the path's hero channel, chosen once per path) and each event reports the
// density every channel would have given it, so that the path divides by the mean over the
// channels of its whole density (spectral MIS, balance heuristic, over the path: the weights
// stay within 3 however many events it has, where per-event weights would multiply).
#pragma once
#include <algorithm>
#include <memory>
#include <vector>
#include "core/math.h"
#include "core/media/phase.h"
#include "core/sampler.h"

namespace caustica {

// What free-flight sampling found along [0, tmax] of a ray.
struct MediumEvent {
  bool scattered = false;  // at t (< tmax); else the ray reaches tmax
  float t = 0.0f;
  // The path throughput's factor before the division by its density: sigma_s * Tr(t) where it
  // scattered, Tr(tmax) where it passed.
  Color weight{1.0f};
  // Per channel, the density of this event had that channel been the one sampled: sigma_t *
  // Tr(t) (scattered), Tr(tmax) (passed); 1 for events every channel takes alike.
  Color pdf{1.0f};
  // The event's density under one-sample MIS over the tracked channel, chosen uniformly for
  // this flight alone (balance heuristic: the mean of the channels'); 0 where the tracked
  // channel's own is, which ends the path.
  float flight_pdf(int hero) const { return pdf[hero] > 0.0f ? average(pdf) : 0.0f; }
};

// The null collisions of a chromatic free flight, for estimates taken all along it (the beam
// radiance estimate). Up to a point t of the flight, each channel's ratio-tracking product
// prod (1 - sigma_c / majorant) over the null collisions before t, divided by the mean over the
// channels of the same product (the density of those decisions had that channel been tracked:
// one-sample MIS over a hero channel chosen uniformly, balance heuristic), times whether the
// flight passed t, estimates each channel's transmittance to t without bias; the weights stay
// within 3 where dividing by the hero's own product would not. Empty for a grey extinction.
struct FlightRecord {
  std::vector<float> t;      // the null collisions, in order
  std::vector<Color> ratio;  // after each, the products so far over their mean
  void clear() {
    t.clear();
    ratio.clear();
  }
  // The weight of the point at distance s: the ratio after the last collision before it.
  Color at(float s) const {
    const size_t n = size_t(std::lower_bound(t.begin(), t.end(), s) - t.begin());
    return n == 0 ? Color(1.0f) : ratio[n - 1];
  }
};

// A path's throughput through media under spectral MIS (hero-channel sampling) is beta / mean(r):
// beta the product of its factors, r per channel the product of its medium events' densities
// had that channel been the one sampled (the hero channel samples them all).
inline Color hero_throughput(const Color& beta, const Color& r) { return beta * (3.0f / (r.x + r.y + r.z)); }
// Takes a medium event into beta and r, both kept divided by r[hero]: their products would
// otherwise underflow within a few dozen events in a thin medium (r to 0 first, an infinite
// throughput). False when the path ends there (no weight, or no density in the hero channel).
inline bool take_medium_event(const MediumEvent& event, int hero, Color& beta, Color& r) {
  beta *= event.weight;
  r *= event.pdf;
  const float k = r[hero];
  if (!(k > 0.0f)) return false;
  beta /= k;
  r /= k;
  return !is_black(beta);
}

class Medium {
 public:
  virtual ~Medium() = default;
  // Free-flight sampling along ray (unit direction) over [0, tmax] (tmax may be infinite), by
  // channel `channel`'s extinction (0, 1 or 2). `record`, where given, is cleared and receives
  // the flight's null collisions where the extinction is chromatic.
  virtual MediumEvent sample(const Ray& ray, float tmax, int channel, Sampler& sampler,
                             FlightRecord* record = nullptr) const = 0;
  // Transmittance over [0, tmax] (an unbiased estimate where the medium is not homogeneous).
  virtual Color transmittance(const Ray& ray, float tmax, Sampler& sampler) const = 0;
  virtual const PhaseFunction& phase() const = 0;
  // The scattering coefficient at p (0 where the medium is empty).
  virtual Color sigma_s(const Vec3& p) const = 0;
  // Whether the medium is the same everywhere; then its coefficients (transmittance analytic).
  virtual bool homogeneous(Color& sigma_t, Color& sigma_s) const {
    (void)sigma_t, (void)sigma_s;
    return false;
  }
};

// Which medium lies on each side of a surface: indices into Scene::media, -1 for none
// (vacuum). Interior is the side the geometric normal points away from.
struct MediumInterface {
  int32_t interior = -1, exterior = -1;
  // The medium a ray in direction dir enters through a surface of geometric normal n.
  int32_t entered(const Vec3& dir, const Vec3& n) const { return glm::dot(dir, n) < 0.0f ? interior : exterior; }
};

}  // namespace caustica
