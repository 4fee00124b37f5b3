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

// Centroid bin from (centroid - lo) * kBins / extent. When the extent overflows to inf (centroids
// near +-3e38) that product is inf * 0 = NaN, and converting NaN to int is undefined behaviour
// (UBSan, scene fuzzing): clamp as a float first, NaN going to bin 0.
inline int centroid_bin(float scaled) {
  return scaled > 0.0f ? static_cast<int>(std::min(scaled, float(kBins - 1))) : 0;
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
  nodes_.reserve(2 * items.size() + 2);
  prims_.reserve(input_.size());
  // The root, then a pad: every pair of siblings then starts at an even index, so with the
  // 64-byte aligned storage both children's boxes arrive in one cache line.
  nodes_.resize(2);
  build_node(items, 0, static_cast<uint32_t>(items.size()), 0, 0);
  accel_.clear();
  accel_.reserve(prims_.size());
  for (const Primitive& p : prims_) {
    if (p.kind == ShapeKind::Sphere) accel_.push_back({p.p0, Vec3(p.radius(), 0, 0), Vec3(0.0f), p.kind});
    else if (p.kind == ShapeKind::Triangle) accel_.push_back({p.p0, p.p1 - p.p0, p.p2 - p.p0, p.kind});
    else accel_.push_back({Vec3(0.0f), Vec3(0.0f), Vec3(0.0f), p.kind});
  }
  input_.clear();
  input_.shrink_to_fit();
}

void Bvh::build_node(std::vector<BuildItem>& items, uint32_t begin, uint32_t end, int depth, uint32_t index) {
  Bounds bounds, centroids;
  for (uint32_t i = begin; i < end; ++i) {
    bounds.extend(items[i].bounds);
    centroids.extend(items[i].centroid);
  }
  const uint32_t n = end - begin;
  auto make_leaf = [&] {
    nodes_[index] = {bounds, static_cast<uint32_t>(prims_.size()), static_cast<uint16_t>(n), 0};
    for (uint32_t i = begin; i < end; ++i) prims_.push_back(input_[items[i].index]);
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
      const int b = centroid_bin((items[i].centroid[axis] - centroids.lo[axis]) * scale);
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
      return centroid_bin((it.centroid[best_axis] - lo) * scale) <= best_bin;
    });
    mid = static_cast<uint32_t>(it - items.begin());
  } else {
    mid = begin + n / 2;
  }
  if (mid == begin || mid == end) mid = begin + n / 2;
  const int axis = best_axis >= 0 ? best_axis : 0;
  const uint32_t left = static_cast<uint32_t>(nodes_.size());
  nodes_.resize(nodes_.size() + 2);
  build_node(items, begin, mid, depth + 1, left);
  build_node(items, mid, end, depth + 1, left + 1);
  nodes_[index] = {bounds, left, 0, static_cast<uint16_t>(axis)};
}

template <bool AnyHit>
bool Bvh::traverse(const Ray& ray, Hit& hit) const {
  if (nodes_.empty()) return false;
  const Vec3 inv_dir = 1.0f / ray.dir;
  const bool dir_neg[3] = {ray.dir.x < 0, ray.dir.y < 0, ray.dir.z < 0};
  struct Entry {
    uint32_t node;
    float tnear;
  };
  Entry stack[128];  // depth <= kMaxDepth + 32
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
        const Accel& a = accel_[i];
        float t, u, v;
        const bool h = a.kind == ShapeKind::Triangle ? intersect_triangle_edges(ray, a.p0, a.e1, a.e2, tmax, t, u, v)
                       : a.kind == ShapeKind::Sphere ? intersect_sphere(ray, a.p0, a.e1.x, tmax, t)
                                                     : intersect_primitive(ray, prims_[i], tmax, t);
        if (h) {
          if (AnyHit) return true;
          tmax = t;
          hit.t = t;
          hit.prim = i;
          found = true;
        }
      }
    } else {
      // Visit the near child first; push the far one with its entry distance.
      uint32_t first = nd.offset, second = nd.offset + 1;
      if (dir_neg[nd.axis]) std::swap(first, second);
      float t_first, t_second;
      const bool h1 = hit_box(nodes_[first].bounds, ray.origin, inv_dir, tmax, t_first);
      const bool h2 = hit_box(nodes_[second].bounds, ray.origin, inv_dir, tmax, t_second);
      if (h1 && h2) {
        if (t_second < t_first) {
          std::swap(first, second);
          std::swap(t_first, t_second);
        }
        stack[sp++] = {second, t_second};
        node = first;
        continue;
      }
      if (h1 || h2) {
        node = h1 ? first : second;
        continue;
      }
    }
    // Pop until a node that the ray enters before the closest hit so far.
    bool next = false;
    while (sp > 0) {
      const Entry e = stack[--sp];
      if (e.tnear <= tmax) {
        node = e.node;
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

namespace caustica {
size_t Bvh::memory_bytes() const { return nodes_.capacity() * sizeof(Node) + accel_.capacity() * sizeof(Accel); }
}  // namespace caustica
