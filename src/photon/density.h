// Density estimation on photon maps (Jensen 1996) and precomputed irradiance (Christensen 1999).
#pragma once
#include <algorithm>
#include <vector>
#include "core/bsdf/bsdf.h"
#include "core/scene.h"
#include "photon/photon_map.h"
#include "photon/point_grid.h"

namespace caustica {

struct EstimateSettings {
  size_t k = 50;             // nearest photons gathered
  float max_radius = 1.0f;   // search radius limit
  bool cone_filter = false;  // Jensen's cone filter, weight 1 - d / (cone_k r)
  float cone_k = 1.1f;
  // Every photon within max_radius instead of the k nearest (SPPM's per-pixel radius).
  bool fixed_radius = false;
  // The disc found (k nearest, or max_radius) shrunk to this fraction of its area, counting the
  // photons inside the smaller disc: progressive photon mapping's radius schedule applied to an
  // adaptive first radius.
  float radius2_scale = 1.0f;
  // Only photons stored after min_bounces..max_bounces bounces count (Photon::bounces), so
  // that a light path joined to an eye path stays within max_depth. The disc is still the
  // one the k nearest photons of any bounce count span: the estimate is of the subset's density.
  int min_bounces = 0;
  int max_bounces = 1 << 30;
};

// The estimate settings with the bounce window [min_bounces, max_bounces].
inline EstimateSettings with_bounces(EstimateSettings s, int min_bounces, int max_bounces) {
  s.min_bounces = min_bounces;
  s.max_bounces = max_bounces;
  return s;
}

struct EstimateInfo {
  size_t photons = 0;  // photons used (after the normal and side tests)
  float radius = 0;    // radius of the estimate's disc
  size_t found = 0;    // photons the search returned (its cost)
};

// Reflected radiance towards wo at a surface hit, from the k nearest photons:
// L = sum f_r(wi_p, wo) dPhi_p / (pi r^2) (Jensen 1996, eq. 6), f_r in the hit's shading frame
// at its texture coordinates; with the cone filter the sum is weighted by w_p = 1 - d_p / (k r)
// and normalised by 1 - 2 / (3k). Photons from behind the surface, or whose normal disagrees
// with the geometric normal, are skipped.
Color radiance_estimate(const PhotonMap& map, const SurfaceHit& hit, const Vec3& wo, const EstimateSettings& s,
                        std::vector<Neighbour>& scratch, EstimateInfo* info = nullptr);

// Irradiance E = sum dPhi_p / (pi r^2) on the side of n that `side` points to.
Color irradiance_estimate(const PhotonMap& map, const Vec3& p, const Vec3& n_side, const EstimateSettings& s,
                          std::vector<Neighbour>& scratch, EstimateInfo* info = nullptr);

// Irradiance precomputed at a 1 / stride share of the global map's photons (Christensen 1999),
// each estimated from the other photons (build). Lookups read the nearest precomputed point
// whose normal agrees, carried to the lookup's point along the irradiance's gradient there,
// instead of a k-NN estimate: unbiased on a uniform density at any progressive disc size, and
// in a gradient (tests/photon/density_test.cpp).
class IrradianceCache {
 public:
  // The points' irradiance counts the photons s admits (its bounce window included), and, for
  // levels l = 1 .. levels - 1, the photons of the narrower window min_bounces .. max_bounces - l
  // (the gathers from deeper eye vertices): one k-NN search per point serves them all.
  void build(const PhotonMap& global, size_t stride, const EstimateSettings& s, int levels = 1);
  // The level that holds the irradiance of estimate settings s's bounce window, or -1.
  int level_for(const EstimateSettings& s) const;
  // False when no precomputed point with an agreeing normal lies within max_radius.
  bool lookup(const Vec3& p, const Vec3& n_side, float max_radius, int level, Color& E,
              std::vector<Neighbour>& scratch) const;
  size_t size() const { return points_.size(); }
  size_t memory_bytes() const {
    return points_.memory_bytes() + grid_.memory_bytes() + narrower_.capacity() * sizeof(Color) + gradient_.capacity() * sizeof(Vec3);
  }
  // The kd-tree answers what the grid leaves undecided. Its lookups are 1-NN: small leaves
  // beat the photon maps' 32 here (bench: BM_FinalGather).
  static constexpr size_t kLeafSize = 8;

 private:
  Color value(size_t i, int level) const {
    return level == 0 ? points_.power(uint32_t(i)) : narrower_[i * size_t(levels_ - 1) + size_t(level - 1)];
  }
  // Point i's irradiance carried to p along its gradient (the nearest point tends to lie on
  // the bright side of a gradient: points are photons, denser where the light is).
  Color corrected(size_t i, const Vec3& p, int level) const {
    const float f = 1.0f + glm::dot(gradient_[i], p - points_[uint32_t(i)].position);
    return value(i, level) * std::clamp(f, 0.0f, 3.0f);
  }
  std::vector<Vec3> gradient_;  // of the irradiance over itself, per point, in points_'s order
  PhotonMap points_;  // records reused: power = irradiance, normal = surface normal
  PointGrid grid_;    // the same points, by index: most lookups end here
  std::vector<Color> narrower_;  // levels - 1 per point, in points_'s order
  EstimateSettings settings_;
  int levels_ = 1;
};

// Progressive photon mapping's radius schedule (Knaus and Zwicker 2011, eq. 14): the squared
// radius of pass `pass` (0-based) over the first pass's, prod_{j=1..pass} (j + alpha) / (j + 1).
// It falls like pass^(alpha - 1): the bias vanishes while the variance of the mean still does.
double progressive_radius2_scale(int pass, double alpha);

// True when a photon's stored normal agrees with the query's (both on the same side).
inline bool normals_agree(const Vec3& a, const Vec3& b) { return glm::dot(a, b) > 0.9f; }

}  // namespace caustica
