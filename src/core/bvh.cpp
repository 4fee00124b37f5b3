// Binned SAH BVH (Wald 2007, "On fast construction of SAH-based BVHs").
#include "core/bvh.h"
#include <algorithm>

namespace caustica {
namespace {
constexpr int kBins = 16;
constexpr uint32_t kMaxLeaf = 4;
constexpr int kMaxDepth = 90;
constexpr float kTraversalCost = 1.0f;  // relative to one primitive test

inline bool hit_box(const Bounds& b, const Vec3& org, const Vec3& inv_dir, float tmax, float& tnear) {
  const Vec3 t0 = (b.lo - org) * inv_dir;
  const Vec3 t1 = (b.hi - org) * inv_dir;
  const Vec3 tmin = glm::min(t0, t1), tfar = glm::max(t0, t1);
  tnear = std::max(std::max(tmin.x, tmin.y), std::max(tmin.z, 0.0f));
  const float tf = std::min(std::min(tfar.x, tfar.y), std::min(tfar.z, tmax));
  return tnear <= tf * 1.00000024f;  // two ulps of slack so thin boxes are never missed
}
}  // namespace

void Bvh::build(std::vector<Primitive> prims) {
  input_ = std::move(prims);
  nodes_.clear();
  prims_.clear();
  if (input_.empty()) return;
  std::vector<BuildItem> items(input_.size());
  for (uint32_t i = 0; i < items.size(); ++i)
    items[i] = {input_[i].bounds(), input_[i].centroid(), i};
  nodes_.reserve(2 * items.size());
  prims_.reserve(input_.size());
  build_node(items, 0, static_cast<uint32_t>(items.size()), 0);
  input_.clear();
  input_.shrink_to_fit();
}

uint32_t Bvh::build_node(std::vector<BuildItem>& items, uint32_t begin, uint32_t end, int depth) {
  const uint32_t index = static_cast<uint32_t>(nodes_.size());
  nodes_.push_back({});
  Bounds bounds, centroids;
  for (uint32_t i = begin; i < end; ++i) {
    bounds.extend(items[i].bounds);
    centroids.extend(items[i].centroid);
  }
  const uint32_t n = end - begin;
  auto make_leaf = [&] {
    nodes_[index] = {bounds, static_cast<uint32_t>(prims_.size()), static_cast<uint16_t>(n), 0};
    for (uint32_t i = begin; i < end; ++i) prims_.push_back(input_[items[i].index]);
    return index;
  };
  if (n <= 1) return make_leaf();

  // Find the cheapest split over kBins centroid bins on each axis.
  float best_cost = kInfinity;
  int best_axis = -1, best_bin = 0;
  const Vec3 cext = centroids.extent();
  // Past kMaxDepth, split by count: the tree then stays within the traversal stack.
  for (int axis = 0; axis < 3 && depth < kMaxDepth; ++axis) {
    if (!(cext[axis] > 0.0f)) continue;
    Bounds bin_bounds[kBins];
    uint32_t bin_count[kBins] = {};
    const float scale = kBins / cext[axis];
    for (uint32_t i = begin; i < end; ++i) {
      int b = static_cast<int>((items[i].centroid[axis] - centroids.lo[axis]) * scale);
      b = std::clamp(b, 0, kBins - 1);
      bin_bounds[b].extend(items[i].bounds);
      ++bin_count[b];
    }
    float right_area[kBins];
    uint32_t right_count[kBins];
    Bounds acc;
    uint32_t cnt = 0;
    for (int b = kBins - 1; b > 0; --b) {
      acc.extend(bin_bounds[b]);
      cnt += bin_count[b];
      right_area[b] = acc.surface_area();
      right_count[b] = cnt;
    }
    acc = Bounds{};
    cnt = 0;
    for (int b = 0; b < kBins - 1; ++b) {
      acc.extend(bin_bounds[b]);
      cnt += bin_count[b];
      if (cnt == 0 || right_count[b + 1] == 0) continue;
      const float cost = acc.surface_area() * cnt + right_area[b + 1] * right_count[b + 1];
      if (cost < best_cost) {
        best_cost = cost;
        best_axis = axis;
        best_bin = b;
      }
    }
  }
  const float leaf_cost = bounds.surface_area() * n;
  const float split_cost = kTraversalCost * bounds.surface_area() + best_cost;
  if (best_axis < 0 && n <= kMaxLeaf) return make_leaf();
  if (best_axis >= 0 && n <= kMaxLeaf && split_cost >= leaf_cost) return make_leaf();
  uint32_t mid;
  if (best_axis >= 0) {
    const float scale = kBins / cext[best_axis];
    const float lo = centroids.lo[best_axis];
    auto it = std::partition(items.begin() + begin, items.begin() + end, [&](const BuildItem& it) {
      int b = std::clamp(static_cast<int>((it.centroid[best_axis] - lo) * scale), 0, kBins - 1);
      return b <= best_bin;
    });
    mid = static_cast<uint32_t>(it - items.begin());
  } else {
    mid = begin + n / 2;
  }
  if (mid == begin || mid == end) mid = begin + n / 2;
  const int axis = best_axis >= 0 ? best_axis : 0;
  build_node(items, begin, mid, depth + 1);
  const uint32_t right = build_node(items, mid, end, depth + 1);
  nodes_[index] = {bounds, right, 0, static_cast<uint16_t>(axis)};
  return index;
}

template <bool AnyHit>
bool Bvh::traverse(const Ray& ray, Hit& hit) const {
  if (nodes_.empty()) return false;
  const Vec3 inv_dir = 1.0f / ray.dir;
  const bool dir_neg[3] = {ray.dir.x < 0, ray.dir.y < 0, ray.dir.z < 0};
  uint32_t stack[128];  // depth <= kMaxDepth + 32
  int sp = 0;
  uint32_t node = 0;
  float tmax = ray.tmax;
  bool found = false;
  float tnear;
  if (!hit_box(nodes_[0].bounds, ray.origin, inv_dir, tmax, tnear)) return false;
  while (true) {
    const Node& nd = nodes_[node];
    if (nd.count > 0) {
      for (uint32_t i = nd.offset; i < nd.offset + nd.count; ++i) {
        float t;
        if (intersect_primitive(ray, prims_[i], tmax, t)) {
          if (AnyHit) return true;
          tmax = t;
          hit.t = t;
          hit.prim = i;
          found = true;
        }
      }
    } else {
      // Visit the near child first; push the far one.
      uint32_t first = node + 1, second = nd.offset;
      if (dir_neg[nd.axis]) std::swap(first, second);
      float t_first, t_second;
      const bool h1 = hit_box(nodes_[first].bounds, ray.origin, inv_dir, tmax, t_first);
      const bool h2 = hit_box(nodes_[second].bounds, ray.origin, inv_dir, tmax, t_second);
      if (h1 && h2) {
        if (t_second < t_first) std::swap(first, second);
        stack[sp++] = second;
        node = first;
        continue;
      }
      if (h1 || h2) {
        node = h1 ? first : second;
        continue;
      }
    }
    // Pop until a node that may still hold something closer.
    bool next = false;
    while (sp > 0) {
      node = stack[--sp];
      if (hit_box(nodes_[node].bounds, ray.origin, inv_dir, tmax, tnear)) {
        next = true;
        break;
      }
    }
    if (!next) break;
  }
  return found;
}

bool Bvh::intersect(const Ray& ray, Hit& hit) const { return traverse<false>(ray, hit); }

bool Bvh::occluded(const Ray& ray) const {
  Hit h;
  return traverse<true>(ray, h);
}

}  // namespace caustica
