// A photon map: photon records in a nanoflann kd-tree (uint32 indices) behind build, knn, radius_query.
#pragma once
#include <memory>
#include <vector>
#include "photon/photon.h"

namespace caustica {

struct Neighbour {
  uint32_t index;
  float dist2;
};

class PhotonMap {
 public:
  PhotonMap();
  ~PhotonMap();
  PhotonMap(PhotonMap&&) noexcept;
  PhotonMap& operator=(PhotonMap&&) noexcept;

  // Takes the photons, orders them along a Morton curve (indices refer to that order) and
  // builds the kd-tree. leaf_size was tuned by bench/ (see BENCHMARKS.md).
  // flux_scale multiplies every record's stored power (see Photon). With `order`, receives for
  // each index of the map the photon's index in `photons`.
  void build(std::vector<Photon> photons, float flux_scale = 1.0f, size_t leaf_size = kDefaultLeafSize,
             std::vector<uint32_t>* order = nullptr);
  Color power(uint32_t i) const { return photons_[i].power() * flux_scale_; }
  float flux_scale() const { return flux_scale_; }
  // The k nearest photons within max_radius, nearest first. Returns how many were found.
  // With eps > 0 the search is approximate: each result is within (1 + eps) times the distance
  // of the true one (nanoflann's pruning rule), which is faster.
  size_t knn(const Vec3& p, size_t k, float max_radius, std::vector<Neighbour>& out, float eps = 0.0f) const;
  // All photons within radius (unsorted).
  size_t radius_query(const Vec3& p, float radius, std::vector<Neighbour>& out) const;

  const std::vector<Photon>& photons() const { return photons_; }
  const Photon& operator[](uint32_t i) const { return photons_[i]; }
  // Multiplies photon i's stored power by w (its position, and so the index, unchanged).
  void scale_power(uint32_t i, float w) {
    Photon& p = photons_[i];
    const Color c = p.power() * w;
    for (int k = 0; k < 3; ++k) p.flux[k] = glm::packHalf1x16(c[k]);
  }
  size_t size() const { return photons_.size(); }
  bool empty() const { return photons_.empty(); }
  // Bytes of photon records plus kd-tree index (nodes and index array).
  size_t memory_bytes() const;

  static constexpr size_t kDefaultLeafSize = 32;
  // From this many photons on, the map is two kd-trees over the two Morton halves, built in
  // parallel (a single nanoflann build takes 0.3 s per million photons).
  static constexpr size_t kSplitThreshold = 500000;

 private:
  struct Tree;
  std::vector<Photon> photons_;
  float flux_scale_ = 1.0f;
  std::unique_ptr<Tree> tree_;
};

}  // namespace caustica
