// The grid's build; queries are in the header.
#include "photon/point_grid.h"
#include <algorithm>
#include <tbb/parallel_for.h>
#include "core/shape.h"

namespace caustica {
namespace {
constexpr uint32_t kLeftOut = ~uint32_t(0);  // cell_of for a point outside the grid
}  // namespace

void PointGrid::build(const std::vector<Vec3>& positions, const std::vector<Vec3>& normals, float per_cell) {
  entries_.clear();
  normals_.clear();
  start_.clear();
  if (positions.empty()) return;
  // Points whose position is not finite are left out (no query can be near them).
  Bounds b;
  for (const Vec3& p : positions) {
    if (is_finite(p)) b.extend(p);
  }
  if (b.empty()) return;
  const Vec3 e = b.extent();
  const double n = double(positions.size());
  // Cell indices are 32-bit.
  const double max_cells = std::min(std::max(8.0 * n, 4096.0), 2147483648.0);
  auto cells_for = [&](float c, int64_t* dims) {
    double total = 1;
    for (int a = 0; a < 3; ++a) {
      dims[a] = int64_t(std::floor(double(e[a]) / double(c))) + 1;
      total *= double(dims[a]);
    }
    return total;
  };
  // First guess: the points spread over the surface of their bounding box (a room's walls);
  // then, twice, scaled by the occupancy found (on surfaces, points per cell go as cell^2).
  const float largest = std::max({e.x, e.y, e.z, 1e-6f});
  float cell = float(std::sqrt(double(b.surface_area()) * double(per_cell) / n));
  // Coincident points (no extent) or a single one: any cell is correct; one unit, then.
  if (!(cell > largest * 1e-5f) || !std::isfinite(cell)) cell = largest > 1e-6f ? largest : 1.0f;
  std::vector<uint32_t> cell_of(positions.size());
  for (int round = 0;; ++round) {
    int64_t dims[3];
    // Never many more cells than points: that bounds the memory for sparse, spread-out points.
    const double total = cells_for(cell, dims);
    if (total > max_cells) {
      cell *= float(std::cbrt(total / max_cells)) * 1.01f;
      continue;
    }
    std::copy(dims, dims + 3, dims_);
    origin_ = b.lo;
    inv_cell_ = 1.0f / cell;
    tbb::parallel_for(size_t(0), positions.size(), [&](size_t i) {
      if (!is_finite(positions[i])) {
        cell_of[i] = kLeftOut;
        return;
      }
      const Vec3 f = (positions[i] - origin_) * inv_cell_;
      int64_t c[3];
      for (int a = 0; a < 3; ++a) c[a] = std::clamp<int64_t>(int64_t(f[a]), 0, dims_[a] - 1);
      cell_of[i] = uint32_t((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]);
    });
    if (round >= 2) break;
    std::vector<uint8_t> used(size_t(total), 0);
    double occupied = 0;
    for (uint32_t c : cell_of) {
      if (c == kLeftOut) continue;
      occupied += used[c] ? 0 : 1;
      used[c] = 1;
    }
    cell *= float(std::clamp(std::sqrt(double(per_cell) / (n / occupied)), 0.25, 4.0));
  }
  cell_ = cell;
  // Counting sort by cell; within a cell, points keep their index order.
  const size_t cells = size_t(dims_[0] * dims_[1] * dims_[2]);
  start_.assign(cells + 1, 0);
  size_t kept = 0;
  for (uint32_t c : cell_of) {
    if (c == kLeftOut) continue;
    ++start_[c + 1];
    ++kept;
  }
  for (size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  std::vector<uint32_t> at(start_.begin(), start_.end() - 1);
  entries_.resize(kept);
  normals_.resize(kept);
  for (size_t i = 0; i < positions.size(); ++i) {
    if (cell_of[i] == kLeftOut) continue;
    const uint32_t slot = at[cell_of[i]]++;
    entries_[slot] = Entry{positions[i], uint32_t(i)};
    normals_[slot] = normals[i];
  }
}

}  // namespace caustica
