// Density estimation on photon maps (Jensen 1996) and precomputed irradiance (Christensen 1999).
#pragma once
#include <vector>
#include "core/material.h"
#include "core/scene.h"
#include "photon/photon_map.h"

namespace caustica {

struct EstimateSettings {
  size_t k = 50;             // nearest photons gathered
  float max_radius = 1.0f;   // search radius limit
  bool cone_filter = false;  // Jensen's cone filter, weight 1 - d / (cone_k r)
  float cone_k = 1.1f;
};

struct EstimateInfo {
  size_t photons = 0;  // photons used (after the normal and side tests)
  float radius = 0;    // radius of the estimate's disc
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

// Irradiance precomputed at every stride-th photon of the global map (Christensen 1999).
// Lookups read the nearest precomputed point whose normal agrees, instead of a k-NN estimate.
class IrradianceCache {
 public:
  void build(const PhotonMap& global, size_t stride, const EstimateSettings& s);
  // False when no precomputed point with an agreeing normal lies within max_radius.
  bool lookup(const Vec3& p, const Vec3& n_side, float max_radius, Color& E, std::vector<Neighbour>& scratch) const;
  size_t size() const { return points_.size(); }
  size_t memory_bytes() const { return points_.memory_bytes(); }
  // Lookups are 1-NN: small leaves beat the photon maps' 32 here (bench: BM_FinalGather).
  static constexpr size_t kLeafSize = 8;

 private:
  PhotonMap points_;  // records reused: power = irradiance, normal = surface normal
};

// True when a photon's stored normal agrees with the query's (both on the same side).
inline bool normals_agree(const Vec3& a, const Vec3& b) { return glm::dot(a, b) > 0.9f; }

}  // namespace caustica
