// kd-tree over photons with nanoflann.
#include "photon/photon_map.h"
#include <nanoflann.hpp>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include "core/shape.h"

namespace caustica {
namespace {

// photons[offset, offset + count) as nanoflann's dataset.
struct PhotonCloud {
  const Photon* photons = nullptr;
  size_t count = 0;
  size_t kdtree_get_point_count() const { return count; }
  float kdtree_get_pt(uint32_t i, size_t dim) const { return photons[i].position[int(dim)]; }
  template <class B>
  bool kdtree_get_bbox(B&) const { return false; }
};

// k nearest within a maximum squared radius: the search prunes at min(radius, k-th distance).
class KnnWithinRadius {
 public:
  using DistanceType = float;
  using IndexType = uint32_t;
  KnnWithinRadius(size_t k, float max_dist2, std::vector<Neighbour>& out) : k_(k), max_dist2_(max_dist2), out_(out) {
    out_.clear();
  }
  size_t size() const { return out_.size(); }
  bool full() const { return out_.size() == k_; }
  float worstDist() const { return full() ? out_.back().dist2 : max_dist2_; }
  bool addPoint(float dist2, uint32_t index) {
    if (dist2 >= worstDist()) return true;
    if (full()) out_.pop_back();
    auto it = out_.end();
    while (it != out_.begin() && (it - 1)->dist2 > dist2) --it;
    out_.insert(it, Neighbour{base + index, dist2});
    return true;
  }
  uint32_t base = 0;  // first photon of the subtree being searched

 private:
  size_t k_;
  float max_dist2_;
  std::vector<Neighbour>& out_;
};

class WithinRadius {
 public:
  using DistanceType = float;
  using IndexType = uint32_t;
  WithinRadius(float dist2, std::vector<Neighbour>& out) : dist2_(dist2), out_(out) { out_.clear(); }
  size_t size() const { return out_.size(); }
  bool full() const { return true; }
  float worstDist() const { return dist2_; }
  bool addPoint(float dist2, uint32_t index) {
    if (dist2 < dist2_) out_.push_back(Neighbour{base + index, dist2});
    return true;
  }
  uint32_t base = 0;

 private:
  float dist2_;
  std::vector<Neighbour>& out_;
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PhotonCloud, float, uint32_t>,
                                                   PhotonCloud, 3, uint32_t>;
}  // namespace

// One kd-tree per contiguous part of the Morton-ordered photons. Large maps are cut in two
// halves (each a compact region, thanks to the ordering) built in parallel: nanoflann 1.4.3
// builds on one thread. Queries visit the part whose box is nearer first and skip a part
// whose box lies beyond the current search radius.
struct PhotonMap::Tree {
  struct Part {
    PhotonCloud cloud;
    uint32_t offset = 0;
    Bounds bounds;
    std::unique_ptr<KdTree> index;
  };
  std::vector<Part> parts;

  template <class Result>
  void search(Result& result, const Vec3& p, const nanoflann::SearchParams& params) const {
    const float q[3] = {p.x, p.y, p.z};
    auto dist2 = [&](const Part& part) {
      const Vec3 d = glm::max(glm::max(part.bounds.lo - p, p - part.bounds.hi), Vec3(0.0f));
      return glm::dot(d, d);
    };
    size_t first = 0;
    for (size_t i = 1; i < parts.size(); ++i)
      if (dist2(parts[i]) < dist2(parts[first])) first = i;
    for (size_t n = 0; n < parts.size(); ++n) {
      const Part& part = parts[(first + n) % parts.size()];
      if (n > 0 && dist2(part) >= result.worstDist()) continue;
      result.base = part.offset;
      part.index->findNeighbors(result, q, params);
    }
  }
};

PhotonMap::PhotonMap() = default;
PhotonMap::~PhotonMap() = default;
PhotonMap::PhotonMap(PhotonMap&&) noexcept = default;
PhotonMap& PhotonMap::operator=(PhotonMap&&) noexcept = default;

namespace {
// Spreads the low 21 bits of v to every third bit (for 63-bit Morton codes).
uint64_t spread_bits(uint32_t v) {
  uint64_t x = v & 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

// Orders photons along a Morton curve: photons near in space become near in memory, which
// roughly halves both the kd-tree build and the k-NN query time (see BENCHMARKS.md).
void sort_spatially(std::vector<Photon>& photons, std::vector<uint32_t>* order) {
  Bounds b;
  for (const Photon& p : photons) b.extend(p.position);
  const Vec3 extent = glm::max(b.extent(), Vec3(1e-30f));
  std::vector<std::pair<uint64_t, uint32_t>> keys(photons.size());
  tbb::parallel_for(size_t(0), photons.size(), [&](size_t i) {
    const Vec3 q = (photons[i].position - b.lo) / extent * 2097151.0f;
    keys[i] = {spread_bits(uint32_t(q.x)) | spread_bits(uint32_t(q.y)) << 1 | spread_bits(uint32_t(q.z)) << 2,
               uint32_t(i)};
  });
  tbb::parallel_sort(keys.begin(), keys.end());  // ties broken by index: deterministic
  std::vector<Photon> sorted(photons.size());
  tbb::parallel_for(size_t(0), photons.size(), [&](size_t i) { sorted[i] = photons[keys[i].second]; });
  photons.swap(sorted);
  if (order) {
    order->resize(keys.size());
    for (size_t i = 0; i < keys.size(); ++i) (*order)[i] = keys[i].second;
  }
}
}  // namespace

void PhotonMap::build(std::vector<Photon> photons, float flux_scale, size_t leaf_size, std::vector<uint32_t>* order) {
  photons_ = std::move(photons);
  sort_spatially(photons_, order);
  flux_scale_ = flux_scale;
  tree_ = std::make_unique<Tree>();
  if (photons_.empty()) return;
  const size_t parts = photons_.size() >= kSplitThreshold ? 2 : 1;
  tree_->parts.resize(parts);
  for (size_t i = 0; i < parts; ++i) {
    Tree::Part& part = tree_->parts[i];
    const size_t begin = photons_.size() * i / parts, end = photons_.size() * (i + 1) / parts;
    part.offset = uint32_t(begin);
    part.cloud.photons = photons_.data() + begin;
    part.cloud.count = end - begin;
    for (size_t k = begin; k < end; ++k) part.bounds.extend(photons_[k].position);
  }
  tbb::parallel_for(size_t(0), parts, [&](size_t i) {
    Tree::Part& part = tree_->parts[i];
    part.index = std::make_unique<KdTree>(3, part.cloud, nanoflann::KDTreeSingleIndexAdaptorParams(leaf_size));
    part.index->buildIndex();
  });
}

size_t PhotonMap::knn(const Vec3& p, size_t k, float max_radius, std::vector<Neighbour>& out, float eps) const {
  out.clear();
  if (!tree_ || tree_->parts.empty() || k == 0) return 0;
  KnnWithinRadius result(k, max_radius * max_radius, out);
  tree_->search(result, p, nanoflann::SearchParams(32, eps));
  return out.size();
}

size_t PhotonMap::radius_query(const Vec3& p, float radius, std::vector<Neighbour>& out) const {
  out.clear();
  if (!tree_ || tree_->parts.empty()) return 0;
  WithinRadius result(radius * radius, out);
  tree_->search(result, p, nanoflann::SearchParams());
  return out.size();
}

size_t PhotonMap::memory_bytes() const {
  size_t bytes = photons_.capacity() * sizeof(Photon);
  if (tree_) {
    for (const Tree::Part& part : tree_->parts) bytes += part.index->usedMemory(*part.index);
  }
  return bytes;
}

}  // namespace caustica
