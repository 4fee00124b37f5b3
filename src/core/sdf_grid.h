// Mitsuba 3's `sdfgrid`: a signed distance function sampled on a grid of nx x ny x nz points
// spanning the unit cube under an affine to_world, negative inside. Its surface is the zero set
// of the trilinear interpolant. Each voxel through which the surface may pass (corner values of
// both signs) is one primitive of the accelerator; a ray meets the interpolant in a voxel where
// a cubic in the ray's parameter has its first root (Hansson-Soderlund, Evans and
// Akenine-Moller 2022, "Ray Tracing of Signed Distance Function Grids", JCGT 11(3)).
#pragma once
#include <cstdint>
#include <vector>
#include "core/math.h"

namespace caustica {

struct Bounds;

class SdfGrid {
 public:
  enum class Normals { Smooth, Analytic };
  // values: nx * ny * nz, x fastest; each dimension at least 2.
  SdfGrid(int nx, int ny, int nz, std::vector<float> values, const glm::mat4& to_world, Normals normals);

  int nx() const { return n_[0]; }
  int ny() const { return n_[1]; }
  int nz() const { return n_[2]; }
  float value(int x, int y, int z) const { return values_[(size_t(z) * size_t(n_[1]) + size_t(y)) * size_t(n_[0]) + size_t(x)]; }
  // The voxels (by the grid index of their lower corner) whose corners hold values of both
  // signs (or a zero): the only ones the surface can pass through.
  std::vector<uint32_t> surface_voxels() const;
  // A voxel's box in world space.
  Bounds voxel_bounds(uint32_t voxel) const;
  // The first crossing of the zero set within `voxel` along `ray` at 0 < t < tmax.
  bool intersect(const Ray& ray, uint32_t voxel, float tmax, float& t) const;
  // The geometric normal at a world point in `voxel` (the interpolant's gradient: outwards), and
  // the shading normal (the grid's `normals`: the same, or the smooth one, continuous across
  // voxels: trilinearly interpolated central-difference gradients of the grid's points).
  Vec3 normal(const Vec3& p, uint32_t voxel) const;
  // `geometric` is normal(p, voxel), which the caller already has.
  Vec3 shading_normal(const Vec3& p, uint32_t voxel, const Vec3& geometric) const;
  // The interpolant at a world point (for tests and brute-force references).
  float eval(const Vec3& p) const;

 private:
  // A world point in voxel coordinates ([0, 1]^3 in `voxel`), and its corner values.
  Vec3 to_voxel(const Vec3& p, uint32_t voxel) const;
  void corners(uint32_t voxel, float c[8]) const;
  Vec3 voxel_gradient(const float c[8], const Vec3& q) const;  // d/d(local), local = unit cube
  Vec3 point_gradient(int x, int y, int z) const;
  Vec3 world_normal(const Vec3& local_gradient) const;

  int n_[3];
  std::vector<float> values_;
  glm::dmat4 to_world_, to_local_;
  glm::dmat3 normal_matrix_;  // the inverse transpose of to_world's linear part
  Normals normals_;
};

}  // namespace caustica
