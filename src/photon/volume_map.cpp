#include "photon/volume_map.h"
#include <algorithm>

namespace caustica {

void VolumePhotonMap::build(std::vector<Photon> photons, float flux_scale) {
  map_.build(std::move(photons), flux_scale);
  nodes_.clear();
  if (map_.empty()) return;
  nodes_.reserve(2 * (map_.size() / kLeafSize + 1));
  build_node(0, uint32_t(map_.size()));
  nodes_.shrink_to_fit();
}

// Halves of the Morton order: each is a compact region, so halving ranges gives a hierarchy
// as tight as splitting space would, at no sorting cost.
uint32_t VolumePhotonMap::build_node(uint32_t begin, uint32_t end) {
  const uint32_t index = uint32_t(nodes_.size());
  nodes_.push_back(Node{Vec3(kInfinity), Vec3(-kInfinity), begin, 0, 0});
  if (end - begin <= kLeafSize) {
    Node& n = nodes_[index];
    n.count = end - begin;
    for (uint32_t i = begin; i < end; ++i) {
      n.lo = glm::min(n.lo, map_[i].position);
      n.hi = glm::max(n.hi, map_[i].position);
    }
    return index;
  }
  const uint32_t mid = begin + (end - begin) / 2;
  const uint32_t a = build_node(begin, mid);
  const uint32_t b = build_node(mid, end);
  Node& n = nodes_[index];
  n.second = b;
  n.lo = glm::min(nodes_[a].lo, nodes_[b].lo);
  n.hi = glm::max(nodes_[a].hi, nodes_[b].hi);
  return index;
}

float VolumePhotonMap::median_knn_radius(size_t k, size_t samples) const {
  if (map_.size() < 2) return 0.0f;
  k = std::min(k + 1, map_.size());  // (the photon itself is its own nearest)
  const size_t n = std::min(samples, map_.size());
  std::vector<float> radii;
  radii.reserve(n);
  std::vector<Neighbour> found;
  for (size_t j = 0; j < n; ++j) {
    const size_t i = (j * map_.size()) / n;
    const size_t got = map_.knn(map_[uint32_t(i)].position, k, 1e18f, found);
    if (got > 0) radii.push_back(std::sqrt(found[got - 1].dist2));
  }
  if (radii.empty()) return 0.0f;
  std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
  return radii[radii.size() / 2];
}

}  // namespace caustica
