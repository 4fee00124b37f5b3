// SDF grids: ray hits through both backends against a brute-force march of the interpolant,
// normals, and a sphere written as a grid against the analytic sphere.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include "core/accel.h"
#include "core/sampling.h"
#include "support/random.h"

using namespace caustica;
using test::random_in_box;

namespace {

// The signed distance to a sphere (centre c, radius r in the unit cube) on n^3 points, perturbed
// by a wave so that the interpolant has curvature the grid does not follow exactly.
SdfGrid sphere_grid(int n, const glm::mat4& to_world, float wave = 0.0f, SdfGrid::Normals normals = SdfGrid::Normals::Smooth) {
  std::vector<float> v;
  for (int z = 0; z < n; ++z) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const Vec3 p = Vec3(float(x), float(y), float(z)) / float(n - 1);
        v.push_back(glm::length(p - Vec3(0.5f)) - 0.3f + wave * std::sin(17.0f * p.x) * std::cos(13.0f * p.y));
      }
    }
  }
  return SdfGrid(n, n, n, std::move(v), to_world, normals);
}

std::vector<Primitive> voxels(const SdfGrid& g) {
  std::vector<Primitive> out;
  for (uint32_t v : g.surface_voxels()) out.push_back(Primitive::sdf_voxel(&g, v));
  return out;
}

// The first zero of the interpolant along the ray: fine steps, then bisection (the reference).
bool brute_force(const SdfGrid& g, const Ray& ray, const Bounds& box, float& t) {
  const Vec3 inv = 1.0f / ray.dir;
  const Vec3 t0 = (box.lo - ray.origin) * inv, t1 = (box.hi - ray.origin) * inv;
  const Vec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
  const float enter = std::max({0.0f, near.x, near.y, near.z}), leave = std::min({ray.tmax, far.x, far.y, far.z});
  if (!(enter < leave)) return false;
  const int steps = 20000;
  double prev_t = enter, prev_f = g.eval(ray.at(enter));
  for (int i = 1; i <= steps; ++i) {
    const double tt = enter + (leave - enter) * double(i) / steps;
    const double f = g.eval(ray.at(float(tt)));
    if ((f <= 0.0) != (prev_f <= 0.0)) {
      double lo = prev_t, hi = tt;
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        if ((g.eval(ray.at(float(mid))) <= 0.0) == (prev_f <= 0.0)) lo = mid;
        else hi = mid;
      }
      t = float(0.5 * (lo + hi));
      return true;
    }
    prev_t = tt, prev_f = f;
  }
  return false;
}

}  // namespace

TEST_CASE("sdfgrid: random rays hit a grid where a brute-force march of the interpolant does, in both backends",
          "[sdfgrid][accel]" TIER_UNIT) {
  // A scaled, rotated and moved grid: the transform must not change the ray's parameter.
  glm::mat4 m = glm::translate(glm::mat4(1.0f), Vec3(1.0f, -2.0f, 0.5f)) *
                glm::rotate(glm::mat4(1.0f), 0.6f, glm::normalize(Vec3(1, 2, 3))) * glm::scale(glm::mat4(1.0f), Vec3(3.0f, 2.0f, 2.5f));
  const SdfGrid grid = sphere_grid(20, m, 0.02f);
  const std::vector<Primitive> prims = voxels(grid);
  REQUIRE(prims.size() > 100);
  REQUIRE(prims.size() < 20u * 20u * 20u / 2);  // only voxels the surface may cross
  Bounds box;
  for (const Primitive& p : prims) box.extend(p.bounds());
  std::vector<std::unique_ptr<Accelerator>> accels;
  accels.push_back(make_accelerator(AccelKind::Bvh, prims));
#ifdef CAUSTICA_EMBREE
  accels.push_back(make_accelerator(AccelKind::Embree, prims));
#endif
  Rng rng(20261206);
  int hits = 0, misses = 0;
  for (int i = 0; i < 600; ++i) {
    // From outside towards the grid, and from points inside the box (some inside the surface).
    const Vec3 target = random_in_box(rng, 0.0f, 1.0f) * (box.hi - box.lo) + box.lo;
    const Vec3 o = i % 3 == 0 ? random_in_box(rng, 0.0f, 1.0f) * (box.hi - box.lo) + box.lo
                              : target + 12.0f * sample_uniform_sphere(Vec2(rng.next_float(), rng.next_float()));
    if (glm::length(target - o) < 1e-3f) continue;
    const Ray ray{o, glm::normalize(target - o), kInfinity};
    float t_ref = 0.0f;
    const bool ref = brute_force(grid, ray, box, t_ref);
    for (const auto& accel : accels) {
      Hit h;
      const bool hit = accel->intersect(ray, h);
      INFO("ray " << i << " through " << accel->name() << ": reference " << ref << " at " << t_ref << ", hit " << hit << " at " << h.t);
      REQUIRE(hit == ref);
      if (hit) {
        CHECK(h.t == Approx(t_ref).epsilon(1e-4).margin(1e-4));
        // The hit is on the zero set, and occluded() agrees with the hit.
        CHECK(std::abs(grid.eval(ray.at(h.t))) < 1e-4f);
        CHECK(accel->occluded(Ray{ray.origin, ray.dir, h.t * 1.01f}));
        CHECK_FALSE(accel->occluded(Ray{ray.origin, ray.dir, h.t * 0.99f}));
      }
    }
    (ref ? hits : misses)++;
  }
  CHECK(hits > 150);
  CHECK(misses > 50);
}

TEST_CASE("sdfgrid: normals point out of the surface; smooth ones are continuous across voxels", "[sdfgrid]" TIER_UNIT) {
  const glm::mat4 m = glm::scale(glm::mat4(1.0f), Vec3(2.0f));
  const SdfGrid analytic = sphere_grid(16, m, 0.0f, SdfGrid::Normals::Analytic);
  const SdfGrid smooth = sphere_grid(16, m, 0.0f, SdfGrid::Normals::Smooth);
  const std::vector<Primitive> prims = voxels(smooth);
  const auto bvh = make_accelerator(AccelKind::Bvh, prims);
  Rng rng(7);
  float worst_analytic = 1.0f, worst_smooth = 1.0f;
  for (int i = 0; i < 400; ++i) {
    // From far out towards the centre (1, 1, 1): the sphere's outward normal is -dir.
    const Vec3 d = sample_uniform_sphere(Vec2(rng.next_float(), rng.next_float()));
    const Ray ray{Vec3(1.0f) + 5.0f * d, -d, kInfinity};
    Hit h;
    REQUIRE(bvh->intersect(ray, h));
    const Primitive& p = bvh->primitives()[h.prim];
    const Vec3 x = ray.at(h.t);
    // The interpolant of a convex distance lies above it between the points: the surface of a
    // 16^3 grid sits 1-1.3 % inside the sphere it samples.
    CHECK(glm::length(x - Vec3(1.0f)) == Approx(0.6f).epsilon(0.02));
    const Vec3 na = analytic.normal(x, p.sdf_voxel()), ns = smooth.shading_normal(x, p.sdf_voxel(), smooth.normal(x, p.sdf_voxel()));
    CHECK(glm::length(na) == Approx(1.0f).epsilon(1e-4));
    CHECK(glm::length(ns) == Approx(1.0f).epsilon(1e-4));
    worst_analytic = std::min(worst_analytic, glm::dot(na, d));
    worst_smooth = std::min(worst_smooth, glm::dot(ns, d));
    CHECK(p.normal_at(x) == na);  // the primitive's geometric normal is the analytic one
  }
  // Both follow the sphere; the smooth one more closely than the voxel-wise gradient.
  CHECK(worst_analytic > 0.97f);
  CHECK(worst_smooth > 0.995f);
  // Continuity: the smooth normal at a point on a face shared by two voxels is the same from both.
  const uint32_t nx = 16, v0 = (8 * nx + 8) * nx + 3;  // voxels (3, 8, 8) and (4, 8, 8) share x = 4
  const Vec3 on_face = Vec3(glm::scale(glm::mat4(1.0f), Vec3(2.0f)) * glm::vec4(4.0f / 15.0f, 8.3f / 15.0f, 8.6f / 15.0f, 1.0f));
  const Vec3 a = smooth.shading_normal(on_face, v0, smooth.normal(on_face, v0)), b = smooth.shading_normal(on_face, v0 + 1, smooth.normal(on_face, v0 + 1));
  CHECK(glm::length(a - b) < 1e-5f);
}
