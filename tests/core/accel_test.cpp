// The ray-casting backends agree: Embree against our BVH (the oracle) on random scenes and rays.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "core/accel.h"
#include "core/bvh.h"
#include "io/json_reader.h"
#include "core/sampling.h"
#include "support/random.h"

using namespace caustica;
using test::random_in_box;

namespace {

std::vector<Primitive> random_scene(Rng& rng, int triangles, int spheres) {
  std::vector<Primitive> prims;
  for (int i = 0; i < triangles; ++i) {
    // Sizes from tiny slivers to a quarter of the box.
    const Vec3 a = random_in_box(rng, -10.0f, 10.0f);
    const float size = 0.01f + 5.0f * rng.next_float() * rng.next_float();
    const Vec3 b = a + size * random_in_box(rng, -1.0f, 1.0f), c = a + size * random_in_box(rng, -1.0f, 1.0f);
    if (glm::length(glm::cross(b - a, c - a)) > 1e-6f) prims.push_back(Primitive::triangle(a, b, c));
  }
  for (int i = 0; i < spheres; ++i) {
    prims.push_back(Primitive::sphere(random_in_box(rng, -10.0f, 10.0f), 0.05f + 1.5f * rng.next_float()));
  }
  return prims;
}

Ray random_ray(Rng& rng) {
  const Vec3 o = random_in_box(rng, -12.0f, 12.0f);
  const Vec3 d = sample_uniform_sphere(Vec2(rng.next_float(), rng.next_float()));
  return Ray{o, d, rng.next_float() < 0.3f ? 1.0f + 20.0f * rng.next_float() : kInfinity};
}

}  // namespace

#ifdef CAUSTICA_EMBREE
TEST_CASE("accel: Embree finds the hits and primitives our BVH finds on random scenes", "[accel]" TIER_UNIT) {
  Rng rng(20261123);
  size_t hits = 0, rays = 0;
  for (int scene = 0; scene < 6; ++scene) {
    const std::vector<Primitive> prims = random_scene(rng, 200 + 400 * scene, scene % 2 == 0 ? 30 : 0);
    const auto bvh = make_accelerator(AccelKind::Bvh, prims);
    const auto embree = make_accelerator(AccelKind::Embree, prims);
    REQUIRE(std::string(embree->name()) == "embree");
    REQUIRE(embree->primitives().size() == prims.size());
    REQUIRE(embree->memory_bytes() > 0);
    size_t mismatches = 0;
    for (int i = 0; i < 4000; ++i, ++rays) {
      const Ray ray = random_ray(rng);
      Hit a, b;
      const bool ha = bvh->intersect(ray, a), hb = embree->intersect(ray, b);
      bool same = ha == hb;
      if (same && ha) {
        ++hits;
        const Primitive& pa = bvh->primitives()[a.prim];
        const Primitive& pb = embree->primitives()[b.prim];
        const bool same_prim = pa.kind == pb.kind && pa.p0 == pb.p0 && pa.p1 == pb.p1 && pa.p2 == pb.p2;
        const bool same_t = std::abs(a.t - b.t) <= 1e-4f * std::max(1.0f, a.t);
        // Another primitive only counts when it is hit at the same distance (touching ones).
        same = same_t && (same_prim || std::abs(a.t - b.t) <= 1e-5f * std::max(1.0f, a.t));
      }
      if (bvh->occluded(ray) != embree->occluded(ray)) same = false;
      if (!same) {
        ++mismatches;
        UNSCOPED_INFO("scene " << scene << " ray " << i << ": bvh " << ha << " t " << a.t << ", embree " << hb << " t "
                               << b.t);
      }
    }
    CHECK(mismatches == 0);
  }
  // The rays were not all misses or all hits.
  CHECK(hits > rays / 10);
  CHECK(hits < rays * 9 / 10);
}

TEST_CASE("accel: a sphere seen from inside and a ray starting on a surface are found by both backends", "[accel]" TIER_UNIT) {
  std::vector<Primitive> prims = {Primitive::sphere(Vec3(0.0f), 2.0f),
                                  Primitive::triangle(Vec3(-1, -1, 0.5f), Vec3(1, -1, 0.5f), Vec3(0, 1, 0.5f))};
  for (AccelKind kind : {AccelKind::Bvh, AccelKind::Embree}) {
    const auto accel = make_accelerator(kind, prims);
    Hit hit;
    // From the centre up +z: the triangle at 0.5, then the sphere at 2.
    REQUIRE(accel->intersect(Ray{Vec3(0.0f), Vec3(0, 0, 1), kInfinity}, hit));
    CHECK(hit.t == Approx(0.5f).epsilon(1e-6));
    REQUIRE(accel->intersect(Ray{Vec3(0, 0, 0.6f), Vec3(0, 0, 1), kInfinity}, hit));
    CHECK(hit.t == Approx(1.4f).epsilon(1e-6));
    CHECK(accel->primitives()[hit.prim].kind == ShapeKind::Sphere);
    // tmax short of the hit: no hit, not occluded.
    CHECK_FALSE(accel->intersect(Ray{Vec3(0, 0, 0.6f), Vec3(0, 0, 1), 1.3f}, hit));
    CHECK_FALSE(accel->occluded(Ray{Vec3(0, 0, 0.6f), Vec3(0, 0, 1), 1.3f}));
    CHECK(accel->occluded(Ray{Vec3(0, 0, 0.6f), Vec3(0, 0, 1), 1.5f}));
  }
}
#else
TEST_CASE("accel: our BVH is the backend when Embree is not built", "[accel]" TIER_UNIT) {
  REQUIRE_FALSE(embree_available());
  REQUIRE(default_accel() == AccelKind::Bvh);
  CHECK_THROWS_AS(make_accelerator(AccelKind::Embree, {Primitive::sphere(Vec3(0.0f), 1.0f)}), InputError);
}
#endif

TEST_CASE("accel: --accel and the scene key choose the backend", "[accel]" TIER_UNIT) {
  AccelKind kind;
  CHECK(parse_accel("bvh", kind));
  CHECK(kind == AccelKind::Bvh);
  CHECK(parse_accel("embree", kind));
  CHECK(kind == AccelKind::Embree);
  CHECK_FALSE(parse_accel("optix", kind));
  CHECK(default_accel() == (embree_available() ? AccelKind::Embree : AccelKind::Bvh));
}
