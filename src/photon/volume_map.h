// The volume photon map (Jensen and Christensen 1998): the points where photons scattered in
// participating media, searched along rays for the beam radiance estimate (Jarosz, Zwicker and
// Jensen 2008) with one radius for every photon (progressive: it shrinks pass by pass).
#pragma once
#include <algorithm>
#include <vector>
#include "core/math.h"
#include "photon/photon_map.h"

namespace caustica {

// A volume photon's record is a Photon: position, flux, the direction it came from (incoming),
// the scattering events before it (bounces); its normal field holds, in place of a direction,
// the medium it scattered in (an estimate along a ray gathers its own medium's photons only)
// and whether its path reached the medium through caustic surfaces alone (L S+ V), which a
// volume caustic map holds as well.
inline uint16_t volume_photon_tag(int32_t medium, bool caustic_path) {
  return uint16_t((uint32_t(std::clamp(medium, 0, 32767)) << 1) | (caustic_path ? 1u : 0u));
}
inline bool is_caustic_path(const Photon& p) { return (p.normal & 1u) != 0; }
inline int32_t photon_medium(const Photon& p) { return int32_t(p.normal >> 1); }

class VolumePhotonMap {
 public:
  // Takes the photons (their stored power times flux_scale is their flux) and indexes them: a
  // kd-tree (PhotonMap: Morton order, k-NN) and a bounding-volume hierarchy over that order
  // for the searches along rays.
  void build(std::vector<Photon> photons, float flux_scale);
  const PhotonMap& photons() const { return map_; }
  void scale_power(uint32_t i, float w) { map_.scale_power(i, w); }
  size_t size() const { return map_.size(); }
  bool empty() const { return map_.empty(); }
  // The median distance to the k-th nearest other photon over up to `samples` photons spread
  // through the map (deterministic); 0 when the map is empty.
  float median_knn_radius(size_t k, size_t samples = 512) const;
  // Calls f(index, t, d2) for every photon within `radius` of the line of ray (unit direction)
  // whose projection t on it lies in [tmin, tmax]; d2 its squared distance from the line.
  template <class F>
  void along(const Ray& ray, float tmin, float tmax, float radius, F&& f) const;
  // Bytes of records, kd-tree and hierarchy.
  size_t memory_bytes() const { return map_.memory_bytes() + nodes_.capacity() * sizeof(Node); }
  static constexpr uint32_t kLeafSize = 8;

 private:
  // Depth-first: a node's first child follows it; `second` is the other's index. A leaf holds
  // photons [first, first + count).
  struct Node {
    Vec3 lo, hi;
    uint32_t first, count;  // count 0: an inner node
    uint32_t second;
  };
  uint32_t build_node(uint32_t begin, uint32_t end);
  PhotonMap map_;
  std::vector<Node> nodes_;
};

template <class F>
void VolumePhotonMap::along(const Ray& ray, float tmin, float tmax, float radius, F&& f) const {
  if (nodes_.empty()) return;
  const Vec3 inv(1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z);
  const float r2 = radius * radius;
  uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    // The segment against the node's box grown by the radius (slabs).
    float t0 = tmin, t1 = tmax;
    bool miss = false;
    for (int a = 0; a < 3 && !miss; ++a) {
      const float lo = node.lo[a] - radius, hi = node.hi[a] + radius;
      if (ray.dir[a] == 0.0f) {
        miss = ray.origin[a] < lo || ray.origin[a] > hi;
        continue;
      }
      float ta = (lo - ray.origin[a]) * inv[a], tb = (hi - ray.origin[a]) * inv[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
      miss = t0 > t1;
    }
    if (miss) continue;
    if (node.count == 0) {
      stack[top++] = node.second;
      stack[top++] = uint32_t(&node - nodes_.data()) + 1;
      continue;
    }
    for (uint32_t i = node.first; i < node.first + node.count; ++i) {
      const Vec3 d = map_[i].position - ray.origin;
      const float t = glm::dot(d, ray.dir);
      if (t < tmin || t > tmax) continue;
      const Vec3 off = d - t * ray.dir;  // (not |d|^2 - t^2: that cancels far from the origin)
      const float d2 = glm::dot(off, off);
      if (d2 < r2) f(i, t, d2);
    }
  }
}

}  // namespace caustica
