#include "core/media/volume.h"
#include <algorithm>
#include <cmath>

namespace caustica {

std::unique_ptr<Volume> ConstVolume::create(const Params& p) { return std::make_unique<ConstVolume>(p.color("value")); }

GridVolume::GridVolume(VolumeGrid grid) : grid_(std::move(grid)) {
  for (float v : grid_.values) max_ = std::max(max_, v);
}

Color GridVolume::voxel(int x, int y, int z) const {
  const size_t i = (size_t(z) * size_t(grid_.ny) + size_t(y)) * size_t(grid_.nx) + size_t(x);
  if (grid_.channels == 1) return Color(grid_.values[i]);
  return Color(grid_.values[3 * i], grid_.values[3 * i + 1], grid_.values[3 * i + 2]);
}

Color GridVolume::eval(const Vec3& p) const {
  const Vec3 q = (p - grid_.box.lo) / grid_.box.extent();  // [0, 1] inside the box
  if (!(q.x >= 0.0f && q.y >= 0.0f && q.z >= 0.0f && q.x <= 1.0f && q.y <= 1.0f && q.z <= 1.0f)) return Color(0.0f);
  const int n[3] = {grid_.nx, grid_.ny, grid_.nz};
  int i0[3], i1[3];
  float f[3];
  for (int a = 0; a < 3; ++a) {
    const float x = q[a] * float(n[a] - 1);
    i0[a] = std::clamp(int(std::floor(x)), 0, n[a] - 1);
    i1[a] = std::min(i0[a] + 1, n[a] - 1);
    f[a] = std::clamp(x - float(i0[a]), 0.0f, 1.0f);
  }
  auto along_x = [&](int y, int z) { return glm::mix(voxel(i0[0], y, z), voxel(i1[0], y, z), f[0]); };
  const Color low = glm::mix(along_x(i0[1], i0[2]), along_x(i1[1], i0[2]), f[1]);
  const Color high = glm::mix(along_x(i0[1], i1[2]), along_x(i1[1], i1[2]), f[1]);
  return glm::mix(low, high, f[2]);
}

std::unique_ptr<Volume> GridVolume::create(const Params& p) { return std::make_unique<GridVolume>(p.volume_grid("filename")); }

}  // namespace caustica
