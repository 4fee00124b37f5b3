// Bounding volume hierarchy: binned SAH build, flattened nodes, iterative traversal.
#pragma once
#include <vector>
#include "core/shape.h"

namespace caustica {

struct Hit {
  float t = kInfinity;
  uint32_t prim = 0;
};

class Bvh {
 public:
  // Takes the primitives and reorders them for traversal.
  void build(std::vector<Primitive> prims);
  const std::vector<Primitive>& primitives() const { return prims_; }
  Bounds bounds() const { return nodes_.empty() ? Bounds{} : nodes_[0].bounds; }
  size_t node_count() const { return nodes_.size(); }

  bool intersect(const Ray& ray, Hit& hit) const;  // closest hit with t < ray.tmax
  bool occluded(const Ray& ray) const;             // any hit with t < ray.tmax

 private:
  struct Node {
    Bounds bounds;
    uint32_t offset;  // leaf: first primitive; interior: index of the second child
    uint16_t count;   // primitives in a leaf; 0 for an interior node
    uint16_t axis;
  };
  struct BuildItem {
    Bounds bounds;
    Vec3 centroid;
    uint32_t index;
  };
  uint32_t build_node(std::vector<BuildItem>& items, uint32_t begin, uint32_t end, int depth);
  template <bool AnyHit>
  bool traverse(const Ray& ray, Hit& hit) const;

  std::vector<Node> nodes_;
  std::vector<Primitive> prims_;
  std::vector<Primitive> input_;
};

}  // namespace caustica
