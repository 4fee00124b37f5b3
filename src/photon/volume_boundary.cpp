#include "photon/volume_boundary.h"
#include <algorithm>
#include <cmath>
#include <tbb/parallel_for.h>
#include "core/bsdf/bsdf.h"
#include "core/sampling.h"
#include "core/scene.h"

namespace caustica {

float medium_ball_fraction(const Scene& scene, const Vec3& p, int32_t medium, float radius, int directions, Rng& rng,
                           uint64_t& rays) {
  if (!(radius > 0.0f) || directions < 1) return 1.0f;
  // Spherical Fibonacci points (equal areas, strata along z) in a random frame, turned about it
  // by a random angle: an unbiased estimate for any orientation of the boundary.
  const Frame frame(sample_uniform_sphere(Vec2(rng.next_float(), rng.next_float())));
  const float spin = rng.next_float();
  constexpr float kGolden = 0.618033988749895f;
  double inside = 0;  // the ball's volume along the directions reached, in units of r^3 / 3
  for (int i = 0; i < directions; ++i) {
    const float z = 1.0f - (2.0f * float(i) + 1.0f) / float(directions);
    const float sxy = std::sqrt(std::max(0.0f, 1.0f - z * z));
    float frac = float(i) * kGolden + spin;
    frac -= std::floor(frac);
    const float phi = 2.0f * kPi * frac;
    const Vec3 dir = frame.to_world(Vec3(sxy * std::cos(phi), sxy * std::sin(phi), z));
    // Along the direction: the stretches in the photon's medium up to the radius (r^3 - a^3
    // of the ball's radial integral per stretch [a, b]).
    Ray ray{p, dir, radius};
    int32_t m = medium;
    for (int crossing = 0; crossing < 32; ++crossing) {
      SurfaceHit hit;
      ++rays;
      const bool found = scene.intersect(ray, hit);
      const float a = radius - ray.tmax, b = found ? a + hit.t : radius;
      if (m == medium) inside += double(b) * b * b - double(a) * a * a;
      if (!found) break;
      if (!Scene::passes_straight(hit)) break;
      if (hit.media) m = hit.media->entered(dir, hit.n);
      ray = Scene::continued(ray, hit);
      if (!(ray.tmax > 0.0f)) break;
    }
  }
  const double fraction = inside / (double(directions) * double(radius) * radius * radius);
  return float(std::clamp(fraction, 0.0, 1.0));
}

uint64_t correct_volume_boundaries(VolumePhotonMap& map, const Scene& scene, float radius, uint64_t seed) {
  if (map.empty() || !(radius > 0.0f)) return 0;
  constexpr size_t kBlock = 1024;
  const size_t n = map.size(), blocks = (n + kBlock - 1) / kBlock;
  std::vector<uint64_t> block_rays(blocks, 0);
  tbb::parallel_for(size_t(0), blocks, [&](size_t b) {
    for (size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      const Photon& photon = map.photons()[uint32_t(i)];
      Rng rng(hash_seed(seed, i, 0x766f6c62));  // "volb"
      const float f = medium_ball_fraction(scene, photon.position, photon_medium(photon), radius,
                                           kBoundaryDirections, rng, block_rays[b]);
      if (f < 1.0f) map.scale_power(uint32_t(i), std::min(1.0f / std::max(f, 1e-6f), kMaxBoundaryWeight));
    }
  });
  uint64_t rays = 0;
  for (uint64_t r : block_rays) rays += r;
  return rays;
}

}  // namespace caustica
