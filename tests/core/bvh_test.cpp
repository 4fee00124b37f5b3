// The BVH against a brute-force linear scan: closest hit, any hit, and degenerate inputs.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <algorithm>
#include <sstream>
#include "core/bvh.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "support/random.h"

using namespace caustica;
using test::next2;
using test::random_in_box;

namespace {
// Each primitive carries its input index in `material`, which the BVH keeps when reordering.
void number(std::vector<Primitive>& prims) {
  for (uint32_t i = 0; i < prims.size(); ++i) prims[i].material = i;
}

std::vector<Primitive> random_scene(uint64_t seed, int triangles, int spheres) {
  Rng rng(seed);
  std::vector<Primitive> prims;
  for (int i = 0; i < triangles; ++i) {
    const Vec3 c = random_in_box(rng, 0, 1);
    prims.push_back(Primitive::triangle(c + random_in_box(rng, -0.05f, 0.05f), c + random_in_box(rng, -0.05f, 0.05f),
                                        c + random_in_box(rng, -0.05f, 0.05f)));
  }
  for (int i = 0; i < spheres; ++i) prims.push_back(Primitive::sphere(random_in_box(rng, 0, 1), 0.01f + 0.09f * rng.next_float()));
  number(prims);
  return prims;
}

bool same_geometry(const Primitive& a, const Primitive& b) {
  return a.kind == b.kind && a.p0 == b.p0 && a.p1 == b.p1 && a.p2 == b.p2;
}

struct Brute {
  bool hit = false;
  float t = kInfinity;
  uint32_t index = 0;
};

Brute brute_closest(const std::vector<Primitive>& prims, const Ray& ray) {
  Brute b;
  for (uint32_t i = 0; i < prims.size(); ++i) {
    float t;
    if (intersect_primitive(ray, prims[i], ray.tmax, t) && t < b.t) {
      b = {true, t, i};
    }
  }
  return b;
}

// Compares the BVH with the linear scan on one ray; returns a description of a mismatch or "".
std::string compare(const Bvh& bvh, const std::vector<Primitive>& prims, const Ray& ray) {
  const Brute expect = brute_closest(prims, ray);
  Hit hit;
  const bool found = bvh.intersect(ray, hit);
  std::ostringstream why;
  why << "ray o=(" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ") d=(" << ray.dir.x << ", "
      << ray.dir.y << ", " << ray.dir.z << ") tmax=" << ray.tmax << ": ";
  if (found != expect.hit) {
    why << "BVH " << (found ? "hits" : "misses") << ", brute force " << (expect.hit ? "hits" : "misses")
        << " (t=" << (found ? hit.t : expect.t) << ")";
    return why.str();
  }
  if (bvh.occluded(ray) != expect.hit) {
    why << "occluded() disagrees with any-hit (" << expect.hit << ")";
    return why.str();
  }
  if (!found) return "";
  if (!(std::abs(hit.t - expect.t) <= 1e-6f * expect.t)) {
    why << "t " << hit.t << " vs " << expect.t;
    return why.str();
  }
  if (hit.prim >= bvh.primitives().size()) return why.str() + "primitive index out of range";
  const Primitive& got = bvh.primitives()[hit.prim];
  if (got.material != expect.index) {
    // A different primitive is fine only if it is hit at the same distance (a tie).
    float t_other;
    if (!intersect_primitive(ray, got, ray.tmax, t_other) || t_other != expect.t) {
      why << "primitive " << got.material << " instead of " << expect.index;
      return why.str();
    }
  } else if (!same_geometry(got, prims[expect.index])) {
    return why.str() + "the reordered primitive's geometry changed";
  }
  return "";
}

void check_rays(const Bvh& bvh, const std::vector<Primitive>& prims, const std::vector<Ray>& rays, double min_hit_fraction) {
  int mismatches = 0, hits = 0;
  std::string first;
  for (const Ray& ray : rays) {
    const std::string m = compare(bvh, prims, ray);
    if (!m.empty() && mismatches++ == 0) first = m;
    Hit h;
    hits += bvh.intersect(ray, h);
  }
  INFO(mismatches << " mismatches; first: " << first);
  CHECK(mismatches == 0);
  CHECK(hits >= min_hit_fraction * rays.size());  // the rays do test something
}

std::vector<Ray> random_rays(Rng& rng, const std::vector<Primitive>& prims, int n, float box_lo, float box_hi) {
  std::vector<Ray> rays;
  for (int i = 0; i < n; ++i) {
    Ray ray;
    ray.origin = random_in_box(rng, box_lo, box_hi);
    if (i % 2 == 0) {
      ray.dir = sample_uniform_sphere(next2(rng));
    } else {  // aimed near a random primitive
      const Primitive& p = prims[size_t(rng.next_float() * prims.size())];
      const Vec3 target = p.centroid() + random_in_box(rng, -0.02f, 0.02f);
      ray.dir = glm::normalize(target - ray.origin);
    }
    if (i % 3 == 0) ray.tmax = 1.5f * rng.next_float();  // finite: tests occluded() and early cut-off
    rays.push_back(ray);
  }
  return rays;
}

void check_permutation(const Bvh& bvh, size_t n) {
  std::vector<uint32_t> ids;
  for (const Primitive& p : bvh.primitives()) ids.push_back(p.material);
  std::sort(ids.begin(), ids.end());
  REQUIRE(ids.size() == n);
  for (uint32_t i = 0; i < n; ++i) REQUIRE(ids[i] == i);
}
}  // namespace

TEST_CASE("bvh: matches a linear scan on random triangles and spheres", "[core][bvh]" TIER_UNIT) {
  for (uint64_t seed : {1u, 2u, 3u}) {
    INFO("seed " << seed);
    const std::vector<Primitive> prims = random_scene(seed, 2000, 20);
    Bvh bvh;
    bvh.build(prims);
    check_permutation(bvh, prims.size());
    CHECK(bvh.node_count() > 1);
    // The root bounds hold every primitive.
    const Bounds root = bvh.bounds();
    for (const Primitive& p : prims) {
      const Bounds b = p.bounds();
      REQUIRE(glm::all(glm::lessThanEqual(root.lo, b.lo)));
      REQUIRE(glm::all(glm::greaterThanEqual(root.hi, b.hi)));
    }
    Rng rng(100 + seed);
    check_rays(bvh, prims, random_rays(rng, prims, 5000, -0.5f, 1.5f), 0.3);
  }
}

TEST_CASE("bvh: the comparison notices a BVH that lost primitives", "[core][bvh]" TIER_UNIT) {
  // Negative control: a BVH over all but the spheres must disagree with the full scan.
  const std::vector<Primitive> prims = random_scene(4, 500, 20);
  Bvh partial;
  partial.build(std::vector<Primitive>(prims.begin(), prims.begin() + 500));
  Rng rng(104);
  int mismatches = 0;
  for (const Ray& ray : random_rays(rng, prims, 2000, -0.5f, 1.5f)) mismatches += !compare(partial, prims, ray).empty();
  CHECK(mismatches > 20);
}

TEST_CASE("bvh: axis-aligned quads and axis-aligned rays", "[core][bvh]" TIER_UNIT) {
  // Flat boxes and directions with zero components (infinite 1/d) are the slab test's edge cases.
  Rng rng(7);
  std::vector<Primitive> prims;
  for (int i = 0; i < 300; ++i) {
    const int axis = i % 3;
    Vec3 o = random_in_box(rng, 0, 1), e1(0.0f), e2(0.0f);
    o[axis] = std::round(o[axis] * 8.0f) / 8.0f;  // planes on a grid, shared by several quads
    e1[(axis + 1) % 3] = 0.05f + 0.2f * rng.next_float();
    e2[(axis + 2) % 3] = 0.05f + 0.2f * rng.next_float();
    prims.push_back(Primitive::triangle(o, o + e1, o + e1 + e2));
    prims.push_back(Primitive::triangle(o, o + e1 + e2, o + e2));
  }
  number(prims);
  Bvh bvh;
  bvh.build(prims);
  check_permutation(bvh, prims.size());
  std::vector<Ray> rays;
  const Vec3 dirs[] = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1),
                       glm::normalize(Vec3(1, 1, 0)), glm::normalize(Vec3(0, -1, 1)), glm::normalize(Vec3(1, 0, -1))};
  for (int i = 0; i < 5000; ++i) {
    Ray ray{random_in_box(rng, -0.2f, 1.2f), dirs[i % 9]};
    if (i % 2 == 0) {
      // Start on a grid plane and run within it: the ray lies in the faces of flat boxes.
      for (int axis = 0; axis < 3; ++axis) {
        if (ray.dir[axis] == 0.0f) ray.origin[axis] = std::round(ray.origin[axis] * 8.0f) / 8.0f;
      }
    }
    if (i % 4 == 0) ray.tmax = 2.0f * rng.next_float();
    rays.push_back(ray);
  }
  check_rays(bvh, prims, rays, 0.2);
}

TEST_CASE("bvh: an empty BVH hits nothing", "[core][bvh]" TIER_UNIT) {
  Bvh bvh;
  const Ray ray{Vec3(0), Vec3(0, 0, 1)};
  Hit hit;
  CHECK_FALSE(bvh.intersect(ray, hit));
  CHECK_FALSE(bvh.occluded(ray));
  bvh.build({});
  CHECK(bvh.node_count() == 0);
  CHECK(bvh.primitives().empty());
  CHECK(bvh.bounds().empty());
  CHECK_FALSE(bvh.intersect(ray, hit));
  CHECK_FALSE(bvh.occluded(ray));
  CHECK(hit.t == kInfinity);
}

TEST_CASE("bvh: a single primitive, and rebuilding replaces the old contents", "[core][bvh]" TIER_UNIT) {
  Bvh bvh;
  bvh.build({Primitive::sphere(Vec3(0, 0, 5), 1.0f)});
  Hit hit;
  REQUIRE(bvh.intersect(Ray{Vec3(0), Vec3(0, 0, 1)}, hit));
  CHECK(hit.t == Approx(4.0f));
  CHECK(hit.prim == 0);
  CHECK_FALSE(bvh.occluded(Ray{Vec3(0), Vec3(0, 0, 1), 3.9f}));
  CHECK(bvh.occluded(Ray{Vec3(0), Vec3(0, 0, 1), 4.1f}));
  bvh.build({Primitive::sphere(Vec3(0, 0, -5), 1.0f)});
  CHECK_FALSE(bvh.intersect(Ray{Vec3(0), Vec3(0, 0, 1)}, hit));
  CHECK(bvh.primitives().size() == 1);
}

TEST_CASE("bvh: 1000 triangles with one centroid", "[core][bvh]" TIER_UNIT) {
  // Every centroid is exactly the origin: no split by centroid is possible.
  Rng rng(8);
  std::vector<Primitive> prims;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a = random_in_box(rng, -1, 1), b = random_in_box(rng, -1, 1);
    prims.push_back(Primitive::triangle(a, b, -(a + b)));
  }
  number(prims);
  Bvh bvh;
  bvh.build(prims);
  check_permutation(bvh, prims.size());
  std::vector<Ray> rays;
  for (int i = 0; i < 2000; ++i) {
    Ray ray{3.0f * sample_uniform_sphere(next2(rng)), Vec3(0.0f)};
    ray.dir = glm::normalize(random_in_box(rng, -0.5f, 0.5f) - ray.origin);
    if (i % 3 == 0) ray.tmax = 3.0f * rng.next_float();
    rays.push_back(ray);
  }
  // Rays from inside the cluster too.
  for (int i = 0; i < 500; ++i) rays.push_back(Ray{random_in_box(rng, -0.3f, 0.3f), sample_uniform_sphere(next2(rng))});
  check_rays(bvh, prims, rays, 0.5);

  // 1000 copies of the same triangle: the hit distance is the same whichever copy is found.
  std::vector<Primitive> copies(1000, Primitive::triangle(Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)));
  number(copies);
  bvh.build(copies);
  check_permutation(bvh, copies.size());
  Hit hit;
  REQUIRE(bvh.intersect(Ray{Vec3(0, 0, -2), Vec3(0, 0, 1)}, hit));
  CHECK(hit.t == 2.0f);
  CHECK_FALSE(bvh.intersect(Ray{Vec3(0, 0, -2), Vec3(0, 0, -1)}, hit));
}
