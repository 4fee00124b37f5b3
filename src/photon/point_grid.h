// Approximate nearest-point queries on a hashed uniform grid, for points that lie on surfaces
// (the precomputed irradiance of the final gather). A query scans the 2x2x2 cells around it and
// answers only when that block decides the question as nanoflann's eps = 1 would: the point
// returned is within twice the distance of the true nearest one. Otherwise it says so, and the
// caller asks its kd-tree.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>
#include "core/math.h"

namespace caustica {

class PointGrid {
 public:
  static constexpr int64_t kNone = -1;       // certainly no accepted point within the radius
  static constexpr int64_t kUndecided = -2;  // the block around the query cannot tell

  // Sorts the points (with their unit normals) into cubic cells sized so that a non-empty cell
  // holds about `per_cell` of them (larger where the cells would outnumber the points 8 to 1).
  // Indices in answers are positions in these arrays.
  void build(const std::vector<Vec3>& positions, const std::vector<Vec3>& normals, float per_cell = 2.0f);

  // The point nearest q among those within max_radius whose normal passes accept(normal), or
  // kNone, or kUndecided. An answer i >= 0 lies within twice the distance of the nearest
  // accepted point. Where points it rejects lie nearer within the scanned block, it is the
  // nearest accepted one and fewer than 8 points lie nearer (as a search of the 8 nearest
  // would find it).
  template <class Accept>
  int64_t nearest(const Vec3& q, float max_radius, Accept&& accept) const;

  float cell_size() const { return cell_; }
  size_t size() const { return entries_.size(); }
  size_t memory_bytes() const {
    return entries_.capacity() * sizeof(Entry) + normals_.capacity() * sizeof(Vec3) + start_.capacity() * sizeof(uint32_t);
  }

 private:
  struct Entry {
    Vec3 p;
    uint32_t index;
  };
  Vec3 origin_{0.0f};
  float cell_ = 1.0f, inv_cell_ = 1.0f;
  int64_t dims_[3] = {0, 0, 0};
  std::vector<Entry> entries_;   // sorted by cell (x fastest, then y, then z)
  std::vector<Vec3> normals_;    // beside entries_
  std::vector<uint32_t> start_;  // first entry of each cell, and the end
};

template <class Accept>
int64_t PointGrid::nearest(const Vec3& q, float max_radius, Accept&& accept) const {
  if (entries_.empty()) return kNone;
  // Per axis, the query's cell and its neighbour on the nearer side: the block reaches at least
  // half a cell beyond q in every direction.
  int64_t lo[3];
  float margin = kInfinity;  // distance from q to the block's boundary
  for (int a = 0; a < 3; ++a) {
    const float f = (q[a] - origin_[a]) * inv_cell_;
    if (!(f >= -1.0f && f <= float(dims_[a] + 1))) return kUndecided;
    const float cell = std::floor(f);
    lo[a] = int64_t(cell) - (f - cell < 0.5f ? 1 : 0);
    margin = std::min(margin, std::min(f - float(lo[a]), float(lo[a] + 2) - f) * cell_);
  }
  float best_d2 = max_radius * max_radius;
  int64_t best = kNone;
  bool rejected = false;  // a point within max_radius that accept() turned down
  const int64_t x0 = std::max<int64_t>(lo[0], 0), x1 = std::min<int64_t>(lo[0] + 2, dims_[0]);
  // Calls visit(entry index, squared distance) for every point of the block.
  auto scan = [&](auto&& visit) {
    for (int64_t z = std::max<int64_t>(lo[2], 0); x0 < x1 && z < std::min<int64_t>(lo[2] + 2, dims_[2]); ++z) {
      for (int64_t y = std::max<int64_t>(lo[1], 0); y < std::min<int64_t>(lo[1] + 2, dims_[1]); ++y) {
        const size_t row = size_t((z * dims_[1] + y) * dims_[0]);
        for (uint32_t i = start_[row + size_t(x0)], end = start_[row + size_t(x1)]; i < end; ++i) {
          const Vec3 d = entries_[i].p - q;
          visit(i, glm::dot(d, d));
        }
      }
    }
  };
  scan([&](uint32_t i, float d2) {
    if (d2 >= best_d2) return;
    if (accept(normals_[i])) {
      best_d2 = d2;
      best = int64_t(entries_[i].index);
    } else {
      rejected = true;
    }
  });
  if (best == kNone) return max_radius <= margin ? kNone : kUndecided;
  const float best_d = std::sqrt(best_d2);
  // Accepted points outside the block are at least `margin` away.
  if (!rejected) return best_d <= 2.0f * margin ? best : kUndecided;
  // Rejected points lie nearer: answer only when every point nearer than `best` is in the block
  // and fewer than 8 of them are.
  if (best_d > margin) return kUndecided;
  int nearer = 0;
  scan([&](uint32_t, float d2) { nearer += d2 < best_d2 ? 1 : 0; });
  return nearer < 8 ? best : kUndecided;
}

}  // namespace caustica
