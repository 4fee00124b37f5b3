// Bounding volume hierarchy: binned SAH build, flattened nodes, iterative traversal.
#pragma once
#include <new>
#include <vector>
#include "core/accel.h"

namespace caustica {

class Bvh final : public Accelerator {
 public:
  // Takes the primitives and reorders them for traversal.
  void build(std::vector<Primitive> prims);
  const std::vector<Primitive>& primitives() const override { return prims_; }
  Bounds bounds() const override { return nodes_.empty() ? Bounds{} : nodes_[0].bounds; }
  size_t node_count() const { return nodes_.size(); }
  size_t memory_bytes() const override;
  const char* name() const override { return "bvh"; }

  bool intersect(const Ray& ray, Hit& hit) const override;  // closest hit with t < ray.tmax
  bool occluded(const Ray& ray) const override;             // any hit with t < ray.tmax

 private:
  struct alignas(32) Node {
    Bounds bounds;
    uint32_t offset;  // leaf: first primitive; interior: index of the first child (the second follows)
    uint16_t count;   // primitives in a leaf; 0 for an interior node
    uint16_t axis;
  };
  // What the hot loop reads: a triangle as a vertex and two edges, or a sphere (p0, radius).
  struct Accel {
    Vec3 p0, e1, e2;
    ShapeKind kind;  // an SDF voxel is tested through prims_
  };
  struct BuildItem {
    Bounds bounds;
    Vec3 centroid;
    uint32_t index;
  };
  void build_node(std::vector<BuildItem>& items, uint32_t begin, uint32_t end, int depth, uint32_t index);
  template <bool AnyHit>
  bool traverse(const Ray& ray, Hit& hit) const;

  // 64-byte aligned, so that sibling pairs (at even indices) share a cache line.
  template <class T>
  struct CacheAligned {
    using value_type = T;
    CacheAligned() = default;
    template <class U>
    CacheAligned(const CacheAligned<U>&) {}
    T* allocate(size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(64))); }
    void deallocate(T* p, size_t) { ::operator delete(p, std::align_val_t(64)); }
    bool operator==(const CacheAligned&) const { return true; }
    bool operator!=(const CacheAligned&) const { return false; }
  };
  std::vector<Node, CacheAligned<Node>> nodes_;
  std::vector<Primitive> prims_;
  std::vector<Accel> accel_;  // parallel to prims_
  std::vector<Primitive> input_;
};

}  // namespace caustica
