// Grid volumes for tests: one channel over a box, values from a function of the point's indices.
#pragma once
#include "core/media/volume.h"

namespace caustica::test {

// An nx x ny x nz one-channel grid over [lo, hi], value(x, y, z) at each point, filled in the
// .vol file's order (x fastest), so a value function drawing random numbers draws them in order.
template <class F>
VolumeGrid make_grid(int nx, int ny, int nz, const Vec3& lo, const Vec3& hi, F value) {
  VolumeGrid g;
  g.nx = nx, g.ny = ny, g.nz = nz;
  g.box.lo = lo;
  g.box.hi = hi;
  g.values.reserve(size_t(nx) * size_t(ny) * size_t(nz));
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) g.values.push_back(float(value(x, y, z)));
  return g;
}

}  // namespace caustica::test
