#include "core/media/volume.h"
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace caustica {

Bounds unit_cube_bounds(const glm::mat4& to_world) {
  Bounds b;
  for (int i = 0; i < 8; ++i) {
    const glm::vec4 c(float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1), 1.0f);
    b.extend(Vec3(to_world * c));
  }
  return b;
}

std::unique_ptr<Volume> ConstVolume::create(const Params& p) {
  const Color value = p.color("value");
  // With a to_world, the unit cube under it (Mitsuba's constvolume in a heterogeneous medium).
  return std::make_unique<ConstVolume>(value, p.has("to_world") ? unit_cube_bounds(p.affine("to_world")) : Bounds{});
}

GridVolume::GridVolume(VolumeGrid grid, const GridPlacement& placement) : grid_(std::move(grid)), placement_(placement) {
  for (float v : grid_.values) max_ = std::max(max_, v);
  // The unit cube to the world: through the file's box and transform, or straight (unit_box).
  glm::dmat4 box_to_world = glm::dmat4(placement_.to_world);
  if (!placement_.unit_box) {
    const glm::dvec3 lo(grid_.box.lo), extent(glm::dvec3(grid_.box.hi) - glm::dvec3(grid_.box.lo));
    box_to_world = box_to_world * glm::dmat4(grid_.to_world) * glm::translate(glm::dmat4(1.0), lo) *
                   glm::scale(glm::dmat4(1.0), glm::max(extent, glm::dvec3(1e-30)));
  }
  to_grid_ = glm::mat4(glm::inverse(box_to_world));
  bounds_ = unit_cube_bounds(glm::mat4(box_to_world));
}

Color GridVolume::voxel(int x, int y, int z) const {
  const size_t i = (size_t(z) * size_t(grid_.ny) + size_t(y)) * size_t(grid_.nx) + size_t(x);
  if (grid_.channels == 1) return Color(grid_.values[i]);
  return Color(grid_.values[3 * i], grid_.values[3 * i + 1], grid_.values[3 * i + 2]);
}

Color GridVolume::eval(const Vec3& p) const {
  Vec3 q = Vec3(to_grid_ * glm::vec4(p, 1.0f));  // [0, 1] inside the box
  const bool inside = q.x >= 0.0f && q.y >= 0.0f && q.z >= 0.0f && q.x <= 1.0f && q.y <= 1.0f && q.z <= 1.0f;
  if (!placement_.cell_centres && !inside) return Color(0.0f);
  q = glm::clamp(q, Vec3(0.0f), Vec3(1.0f));  // (a NaN fails the test above, or clamps to 0)
  const int n[3] = {grid_.nx, grid_.ny, grid_.nz};
  int i0[3], i1[3];
  float f[3];
  for (int a = 0; a < 3; ++a) {
    // The continuous voxel coordinate: voxel i at i (corners) or at the centre of cell i.
    const float x = placement_.cell_centres ? q[a] * float(n[a]) - 0.5f : q[a] * float(n[a] - 1);
    if (placement_.nearest) {
      i0[a] = i1[a] = std::clamp(int(std::floor(x + 0.5f)), 0, n[a] - 1);
      f[a] = 0.0f;
      continue;
    }
    i0[a] = std::clamp(int(std::floor(x)), 0, n[a] - 1);
    i1[a] = std::min(i0[a] + 1, n[a] - 1);
    f[a] = std::clamp(x - float(i0[a]), 0.0f, 1.0f);
  }
  if (placement_.nearest) return voxel(i0[0], i0[1], i0[2]);
  auto along_x = [&](int y, int z) { return glm::mix(voxel(i0[0], y, z), voxel(i1[0], y, z), f[0]); };
  const Color low = glm::mix(along_x(i0[1], i0[2]), along_x(i1[1], i0[2]), f[1]);
  const Color high = glm::mix(along_x(i0[1], i1[2]), along_x(i1[1], i1[2]), f[1]);
  return glm::mix(low, high, f[2]);
}

std::unique_ptr<Volume> GridVolume::create(const Params& p) {
  GridPlacement placement;
  placement.to_world = p.affine("to_world");
  const std::string box = p.string("box", "file");
  if (box != "file" && box != "unit") p.fail("box", "box is \"file\" (the grid file's box) or \"unit\" (the unit cube)");
  placement.unit_box = box == "unit";
  const std::string voxels = p.string("voxels", "corners");
  if (voxels != "corners" && voxels != "centres") {
    p.fail("voxels", "voxels is \"corners\" (Mitsuba 0.6's grids) or \"centres\" (Mitsuba 3's)");
  }
  placement.cell_centres = voxels == "centres";
  const std::string filter = p.string("filter", "trilinear");
  if (filter != "trilinear" && filter != "nearest") p.fail("filter", "filter is \"trilinear\" or \"nearest\"");
  placement.nearest = filter == "nearest";
  return std::make_unique<GridVolume>(p.volume_grid("filename"), placement);
}

}  // namespace caustica
