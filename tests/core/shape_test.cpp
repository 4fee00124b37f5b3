// Ray-triangle and ray-sphere intersection against hand-computed and double-precision answers,
// and the Primitive helpers (area, bounds, normals, surface sampling).
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "support/random.h"
#include "core/shape.h"
#include "io/scene_loader.h"

using namespace caustica;
using test::next2;
using test::random_in_box;

namespace {
// Nearest positive root of |o + t d - c| = r, in long double from the float inputs.
long double sphere_t_reference(const Ray& ray, const Vec3& c, float r) {
  long double f[3], d[3];
  for (int k = 0; k < 3; ++k) {
    f[k] = (long double)ray.origin[k] - (long double)c[k];
    d[k] = ray.dir[k];
  }
  const long double a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const long double b = f[0] * d[0] + f[1] * d[1] + f[2] * d[2];
  const long double cc = f[0] * f[0] + f[1] * f[1] + f[2] * f[2] - (long double)r * r;
  const long double disc = b * b - a * cc;
  if (disc < 0) return -1;
  const long double s = std::sqrt(disc);
  const long double t0 = (-b - s) / a, t1 = (-b + s) / a;
  return t0 > 0 ? t0 : t1;
}

const Vec3 kA(0, 0, 0), kB(1, 0, 0), kC(0, 1, 0);
}  // namespace

TEST_CASE("intersect_triangle: known hits give t and barycentrics", "[core][shape]" TIER_UNIT) {
  float t = -1, u = -1, v = -1;
  Ray ray{Vec3(0.25f, 0.5f, 1.0f), Vec3(0, 0, -1)};
  REQUIRE(intersect_triangle(ray, kA, kB, kC, kInfinity, t, u, v));
  CHECK(t == Approx(1.0f).epsilon(1e-6));
  CHECK(u == Approx(0.25f).epsilon(1e-6));  // weight of p1
  CHECK(v == Approx(0.5f).epsilon(1e-6));   // weight of p2

  // From below (back face) hits too: triangles are two-sided for intersection.
  ray = Ray{Vec3(0.1f, 0.2f, -3.0f), Vec3(0, 0, 1)};
  REQUIRE(intersect_triangle(ray, kA, kB, kC, kInfinity, t, u, v));
  CHECK(t == Approx(3.0f).epsilon(1e-6));
  CHECK(u == Approx(0.1f).epsilon(1e-6));
  CHECK(v == Approx(0.2f).epsilon(1e-6));

  // An oblique ray onto a general triangle at barycentrics (u, v) = (0.3, 0.2), distance 2.5.
  const Vec3 p0(1, 2, 3), p1(4, 1, 2), p2(2, 5, 1);
  const Vec3 q = 0.5f * p0 + 0.3f * p1 + 0.2f * p2;
  const Vec3 d = glm::normalize(Vec3(-0.3f, 0.7f, 0.4f));
  ray = Ray{q - 2.5f * d, d};
  REQUIRE(intersect_triangle(ray, p0, p1, p2, kInfinity, t, u, v));
  CHECK(t == Approx(2.5f).epsilon(1e-5));
  CHECK(u == Approx(0.3f).margin(1e-5));
  CHECK(v == Approx(0.2f).margin(1e-5));
  const Vec3 hit = ray.at(t), from_bary = (1 - u - v) * p0 + u * p1 + v * p2;
  CHECK(glm::length(hit - from_bary) < 1e-5f);
}

TEST_CASE("intersect_triangle: misses", "[core][shape]" TIER_UNIT) {
  float t, u, v;
  // Just outside the hypotenuse, outside each of the other two edges.
  CHECK_FALSE(intersect_triangle(Ray{Vec3(0.501f, 0.5f, 1), Vec3(0, 0, -1)}, kA, kB, kC, kInfinity, t, u, v));
  CHECK_FALSE(intersect_triangle(Ray{Vec3(-0.001f, 0.5f, 1), Vec3(0, 0, -1)}, kA, kB, kC, kInfinity, t, u, v));
  CHECK_FALSE(intersect_triangle(Ray{Vec3(0.5f, -0.001f, 1), Vec3(0, 0, -1)}, kA, kB, kC, kInfinity, t, u, v));
  // Just inside still hits.
  CHECK(intersect_triangle(Ray{Vec3(0.499f, 0.5f, 1), Vec3(0, 0, -1)}, kA, kB, kC, kInfinity, t, u, v));
  // Behind the origin.
  CHECK_FALSE(intersect_triangle(Ray{Vec3(0.2f, 0.2f, -1), Vec3(0, 0, -1)}, kA, kB, kC, kInfinity, t, u, v));
  // Parallel to the plane, above it.
  CHECK_FALSE(intersect_triangle(Ray{Vec3(-1, 0.2f, 1), Vec3(1, 0, 0)}, kA, kB, kC, kInfinity, t, u, v));
  // t >= tmax: the hit at t = 1 counts only for tmax > 1.
  const Ray down{Vec3(0.2f, 0.2f, 1), Vec3(0, 0, -1)};
  CHECK_FALSE(intersect_triangle(down, kA, kB, kC, 1.0f, t, u, v));
  CHECK_FALSE(intersect_triangle(down, kA, kB, kC, 0.5f, t, u, v));
  CHECK(intersect_triangle(down, kA, kB, kC, 1.0001f, t, u, v));
}

TEST_CASE("intersect_triangle: a ray in the plane of the triangle misses", "[core][shape]" TIER_UNIT) {
  float t, u, v;
  for (const Vec3 d : {Vec3(1, 0, 0), Vec3(0, 1, 0), glm::normalize(Vec3(0.6f, 0.8f, 0)), glm::normalize(Vec3(1, -1, 0))}) {
    for (const Vec3 o : {Vec3(-1, 0.25f, 0), Vec3(0.2f, -1, 0), Vec3(0.25f, 0.25f, 0), Vec3(2, 2, 0)}) {
      INFO("origin " << o.x << "," << o.y << " dir " << d.x << "," << d.y);
      CHECK_FALSE(intersect_triangle(Ray{o, d}, kA, kB, kC, kInfinity, t, u, v));
    }
  }
}

TEST_CASE("intersect_sphere: hits from outside, misses, hits from the centre", "[core][shape]" TIER_UNIT) {
  float t = -1;
  const Vec3 c(1, 2, 3);
  const float r = 0.5f;
  Rng rng(3);
  for (int k = 0; k < 100; ++k) {
    const Vec3 w = sample_uniform_sphere(next2(rng));
    const float dist = 2.0f + 10.0f * rng.next_float();
    const Ray ray{c + dist * w, -w};
    REQUIRE(intersect_sphere(ray, c, r, kInfinity, t));
    REQUIRE(t == Approx(dist - r).epsilon(1e-5));
    // Beside the sphere, 1.1 r from the centre line.
    const Vec3 side = Frame(w).s;
    REQUIRE_FALSE(intersect_sphere(Ray{c + dist * w + 1.1f * r * side, -w}, c, r, kInfinity, t));
    // From the centre: t = r in every direction.
    REQUIRE(intersect_sphere(Ray{c, w}, c, r, kInfinity, t));
    REQUIRE(t == Approx(r).epsilon(1e-6));
  }
  // Sphere behind the ray, and a hit beyond tmax.
  CHECK_FALSE(intersect_sphere(Ray{Vec3(0, 0, 5), Vec3(0, 0, 1)}, Vec3(0), 1.0f, kInfinity, t));
  CHECK_FALSE(intersect_sphere(Ray{Vec3(0, 0, -5), Vec3(0, 0, 1)}, Vec3(0), 1.0f, 4.0f, t));
  CHECK(intersect_sphere(Ray{Vec3(0, 0, -5), Vec3(0, 0, 1)}, Vec3(0), 1.0f, 4.001f, t));
  CHECK(t == Approx(4.0f).epsilon(1e-6));
  // Inside with tmax before the surface: no hit.
  CHECK_FALSE(intersect_sphere(Ray{Vec3(0), Vec3(0, 0, 1)}, Vec3(0), 1.0f, 0.999f, t));
}

TEST_CASE("intersect_sphere: rays leaving the surface do not hit it again", "[core][shape]" TIER_UNIT) {
  Rng rng(4);
  int inward_misses = 0, outward_hits = 0, diameter_errors = 0, chord_errors = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 c = random_in_box(rng, -5, 5);
    const float r = 0.1f + 2.9f * rng.next_float();
    const Vec3 n = sample_uniform_sphere(next2(rng));
    const Vec3 p = c + r * n;
    float t;
    // Inward along the diameter: the far side at about 2r.
    const Ray in = spawn_ray(p, n, -n);
    if (!intersect_sphere(in, c, r, kInfinity, t)) {
      ++inward_misses;
    } else if (glm::length(in.at(t) - (c - r * n)) > 1e-3f * r) {
      ++diameter_errors;
    }
    // A random inward direction: the chord, 2 r cos.
    Vec3 d = sample_uniform_sphere(next2(rng));
    if (glm::dot(d, n) > 0) d = -d;
    if (glm::dot(d, n) < -1e-3f) {
      const Ray chord = spawn_ray(p, n, d);
      if (!intersect_sphere(chord, c, r, kInfinity, t)) {
        ++inward_misses;
      } else {
        // About 2 r cos (longer for shallow rays, whose origin moved inside): the far root.
        const double reference = double(sphere_t_reference(chord, c, r));
        if (std::abs(t - reference) > 1e-5 * reference + 1e-6 * r) ++chord_errors;
      }
    }
    // Outward, including nearly tangent directions: a miss.
    Vec3 out = -d;
    if (k % 4 == 0) out = glm::normalize(Frame(n).s + 1e-3f * n);  // grazing, 0.06 degrees above tangent
    if (intersect_sphere(spawn_ray(p, n, out), c, r, kInfinity, t)) ++outward_hits;
  }
  CHECK(inward_misses == 0);
  CHECK(outward_hits == 0);
  CHECK(diameter_errors == 0);
  CHECK(chord_errors == 0);
}

TEST_CASE("intersect_sphere: tangent rays", "[core][shape]" TIER_UNIT) {
  float t;
  const Vec3 c(0.0f);
  CHECK_FALSE(intersect_sphere(Ray{Vec3(0, 1.0001f, -5), Vec3(0, 0, 1)}, c, 1.0f, kInfinity, t));
  const Ray inside{Vec3(0, 0.9999f, -5), Vec3(0, 0, 1)};
  REQUIRE(intersect_sphere(inside, c, 1.0f, kInfinity, t));
  CHECK(double(t) == Approx(double(sphere_t_reference(inside, c, 1.0f))).epsilon(1e-6));
  CHECK(t == Approx(5.0 - std::sqrt(1.0 - 0.9999 * 0.9999)).epsilon(1e-5));
}

TEST_CASE("intersect_sphere: huge radius acts as a plane", "[core][shape]" TIER_UNIT) {
  float t;
  // Ground sphere of radius 1e5 with its top at y = 0, seen from just above.
  const Vec3 c(0, -1e5f, 0);
  const float r = 1e5f;
  Rng rng(5);
  for (int k = 0; k < 1000; ++k) {
    const Vec3 o(20 * rng.next_float() - 10, 0.01f + 2 * rng.next_float(), 20 * rng.next_float() - 10);
    Vec3 d = sample_uniform_sphere(next2(rng));
    if (d.y > -0.05f) continue;
    const Ray ray{o, d};
    REQUIRE(intersect_sphere(ray, c, r, kInfinity, t));
    const long double ref = sphere_t_reference(ray, c, r);
    REQUIRE(double(t) == Approx(double(ref)).epsilon(1e-5));
    // The hit point, in double, lies on the sphere to within 1e-3 of the distance travelled.
    const glm::dvec3 hp = glm::dvec3(o) + double(t) * glm::dvec3(d);
    REQUIRE(std::abs(glm::length(hp - glm::dvec3(c)) - double(r)) < 1e-3 * t);
    // Near the top the sphere is the plane y = 0 bent down by x^2 / 2r.
    REQUIRE(std::abs(hp.y + (hp.x * hp.x + hp.z * hp.z) / (2.0 * r)) < 1e-3 * t);
  }
  // The same sphere far away: distance 9e5 along z.
  const Ray far{Vec3(0), Vec3(0, 0, 1)};
  REQUIRE(intersect_sphere(far, Vec3(0, 0, 1e6f), 1e5f, kInfinity, t));
  CHECK(t == Approx(9e5f).epsilon(1e-6));
  const Ray oblique{Vec3(0), glm::normalize(Vec3(0.05f, 0.02f, 1))};
  REQUIRE(intersect_sphere(oblique, Vec3(0, 0, 1e6f), 1e5f, kInfinity, t));
  CHECK(double(t) == Approx(double(sphere_t_reference(oblique, Vec3(0, 0, 1e6f), 1e5f))).epsilon(1e-6));
}

TEST_CASE("Primitive: area, bounds, centroid", "[core][shape]" TIER_UNIT) {
  const Primitive tri = Primitive::triangle(Vec3(1, 1, 1), Vec3(3, 1, 1), Vec3(1, 4, 1));
  CHECK(tri.area() == Approx(3.0f));
  CHECK(tri.bounds().lo == Vec3(1, 1, 1));
  CHECK(tri.bounds().hi == Vec3(3, 4, 1));
  CHECK(glm::length(tri.centroid() - Vec3(5.0f / 3, 2, 1)) < 1e-6f);

  const Primitive sph = Primitive::sphere(Vec3(1, -2, 3), 2.0f);
  CHECK(sph.radius() == 2.0f);
  CHECK(sph.area() == Approx(16.0 * kPi));
  CHECK(sph.bounds().lo == Vec3(-1, -4, 1));
  CHECK(sph.bounds().hi == Vec3(3, 0, 5));
  CHECK(sph.centroid() == Vec3(1, -2, 3));
  CHECK(sph.bounds().surface_area() == Approx(6 * 16.0));
}

TEST_CASE("Primitive: normal_at follows the winding and flip", "[core][shape]" TIER_UNIT) {
  Primitive tri = Primitive::triangle(kA, kB, kC);  // counter-clockwise seen from +z
  CHECK(glm::length(tri.normal_at(Vec3(0.2f, 0.2f, 0)) - Vec3(0, 0, 1)) < 1e-6f);
  tri.flip = true;
  CHECK(glm::length(tri.normal_at(Vec3(0.2f, 0.2f, 0)) - Vec3(0, 0, -1)) < 1e-6f);
  Primitive swapped = Primitive::triangle(kA, kC, kB);
  CHECK(glm::length(swapped.normal_at(Vec3(0.2f, 0.2f, 0)) - Vec3(0, 0, -1)) < 1e-6f);

  Primitive sph = Primitive::sphere(Vec3(1, 1, 1), 2.0f);
  const Vec3 n = glm::normalize(Vec3(1, -2, 2));
  CHECK(glm::length(sph.normal_at(Vec3(1, 1, 1) + 2.0f * n) - n) < 1e-6f);
  sph.flip = true;
  CHECK(glm::length(sph.normal_at(Vec3(1, 1, 1) + 2.0f * n) + n) < 1e-6f);
}

TEST_CASE("Primitive: sample_point lies on the shape", "[core][shape]" TIER_UNIT) {
  Rng rng(6);
  const Vec3 p0(1, 2, 3), p1(4, 1, 2), p2(2, 5, 1);
  Primitive tri = Primitive::triangle(p0, p1, p2);
  tri.flip = true;
  Primitive sph = Primitive::sphere(Vec3(-1, 2, 0.5f), 1.5f);
  const Vec3 tri_n = -glm::normalize(glm::cross(p1 - p0, p2 - p0));
  Vec3 tri_mean(0.0f);
  for (int k = 0; k < 10000; ++k) {
    Vec3 n;
    const Vec3 p = tri.sample_point(next2(rng), &n);
    tri_mean += p;
    REQUIRE(std::abs(glm::dot(p - p0, tri_n)) < 1e-5f);  // in the plane
    // Inside: all three edge functions have the same sign.
    const float e0 = glm::dot(glm::cross(p1 - p0, p - p0), -tri_n);
    const float e1 = glm::dot(glm::cross(p2 - p1, p - p1), -tri_n);
    const float e2 = glm::dot(glm::cross(p0 - p2, p - p2), -tri_n);
    REQUIRE(e0 >= -1e-5f);
    REQUIRE(e1 >= -1e-5f);
    REQUIRE(e2 >= -1e-5f);
    REQUIRE(glm::length(n - tri_n) < 1e-5f);

    const Vec3 q = sph.sample_point(next2(rng), &n);
    REQUIRE(glm::length(q - Vec3(-1, 2, 0.5f)) == Approx(1.5f).epsilon(1e-5));
    REQUIRE(glm::length(n - glm::normalize(q - Vec3(-1, 2, 0.5f))) < 1e-5f);
  }
  // Uniform by area: the mean is the centroid (standard error ~ 0.01).
  CHECK(glm::length(tri_mean / 10000.0f - tri.centroid()) < 0.05f);
  CHECK(sph.sample_point(Vec2(0.3f, 0.6f), nullptr) == sph.sample_point(Vec2(0.3f, 0.6f), nullptr));
}

namespace {
// A closed, slightly irregular octahedron (8 triangles with outward winding).
struct Octahedron {
  Vec3 v[6] = {{1.1f, 0.05f, 0.02f},  {-0.93f, -0.03f, 0.07f}, {0.04f, 1.07f, -0.05f},
               {-0.02f, -0.97f, 0.03f}, {0.06f, 0.01f, 1.03f},  {-0.05f, 0.04f, -1.01f}};
  int f[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  bool hit(const Ray& ray) const {
    for (const auto& t : f) {
      float tt, u, w;
      if (intersect_triangle(ray, v[t[0]], v[t[1]], v[t[2]], kInfinity, tt, u, w)) return true;
    }
    return false;
  }
};
}  // namespace

TEST_CASE("intersect_triangle: random rays from inside a closed mesh never escape", "[core][shape]" TIER_UNIT) {
  const Octahedron mesh;
  Rng rng(10);
  int escaped = 0;
  for (int k = 0; k < 200000; ++k) {
    const Ray ray{random_in_box(rng, -0.1f, 0.1f), sample_uniform_sphere(next2(rng))};
    escaped += !mesh.hit(ray);
  }
  CHECK(escaped == 0);
}

// Regression: plain Moller-Trumbore let about 12% of rays aimed at shared edges pass between
// the two triangles; the barycentric tests now have a little slack.
TEST_CASE("intersect_triangle: rays aimed at shared edges of a closed mesh do not escape", "[core][regression]" TIER_UNIT) {
  const Octahedron mesh;
  Rng rng(11);
  int escaped = 0;
  const int n = 100000;
  for (int k = 0; k < n; ++k) {
    const int* face = mesh.f[k % 8];
    const Vec3 a = mesh.v[face[0]], b = mesh.v[face[1]];
    const Vec3 on_edge = a + rng.next_float() * (b - a);
    const Vec3 o = random_in_box(rng, -0.1f, 0.1f);
    escaped += !mesh.hit(Ray{o, glm::normalize(on_edge - o)});
  }
  INFO(escaped << " of " << n << " rays escaped through an edge");
  CHECK(escaped == 0);
}

TEST_CASE("shading point: dp/du and dp/dv of spheres and UV-mapped triangles match finite differences", "[core][shape]" TIER_UNIT) {
  // A sphere (u = phi / 2 pi, v = theta / pi about +z) and a quad whose uvs are stretched and
  // sheared against its edges.
  const LoadedScene loaded = parse_scene(R"({"camera": {"position": [0, 0, 9], "look_at": [0, 0, 0]},
    "materials": {"w": {"type": "diffuse"}},
    "objects": [{"type": "sphere", "center": [1, -2, 0.5], "radius": 1.5, "material": "w"},
                {"type": "mesh", "material": "w", "vertices": [[4, 0, 0], [7, 0, 0], [7, 2, 0], [4, 2, 0]],
                 "uvs": [[0, 0], [0.5, 0.25], [0.75, 1.25], [0.25, 1]], "indices": [[0, 1, 2], [0, 2, 3]]}]})",
                                         "s.json", ".");
  const Scene& scene = *loaded.scene;
  Rng rng(11);
  auto world = [](const SurfaceHit& h, const Vec3& v) { return h.frame.to_world(v); };
  int checked = 0;
  for (int i = 0; i < 200; ++i) {
    // Rays at the sphere's upper half (away from the poles) and at the quad.
    const bool sphere = i % 2 == 0;
    const Vec3 target = sphere ? Vec3(1.0f, -2.0f, 0.5f) + 1.5f * glm::normalize(Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, 0.6f))
                               : Vec3(4.2f + 2.6f * rng.next_float(), 0.2f + 1.6f * rng.next_float(), 0.0f);
    const Vec3 origin = target + Vec3(0.0f, 0.0f, 6.0f);
    SurfaceHit h;
    REQUIRE(scene.intersect(Ray{origin, glm::normalize(target - origin), kInfinity}, h));
    const Vec3 dpdu = world(h, h.sp.dpdu), dpdv = world(h, h.sp.dpdv);
    if (sphere) {
      // p(u, v) on the sphere, differentiated numerically.
      auto p = [](double u, double v) {
        const double phi = 2 * 3.14159265358979 * u, theta = 3.14159265358979 * v;
        return glm::dvec3(1, -2, 0.5) + 1.5 * glm::dvec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      };
      const double e = 1e-5, u = h.sp.uv.x, v = h.sp.uv.y;
      const glm::dvec3 du = (p(u + e, v) - p(u - e, v)) / (2 * e), dv = (p(u, v + e) - p(u, v - e)) / (2 * e);
      CHECK(glm::length(glm::dvec3(dpdu) - du) < 1e-3 * glm::length(du) + 1e-4);
      CHECK(glm::length(glm::dvec3(dpdv) - dv) < 1e-3 * glm::length(dv) + 1e-4);
    } else {
      // The quad's affine map from uv to position: solved from its first triangle's corners.
      // (0,0)->(4,0), (0.5,0.25)->(7,0), (0.75,1.25)->(7,2): p = P0 + A (u, v).
      const glm::dmat2 uv(0.5, 0.25, 0.75, 1.25);
      const glm::dmat2 xy(3, 0, 3, 2);
      const glm::dmat2 a = xy * glm::inverse(uv);
      if (h.p.x - 4.0f < 1.5f * h.p.y) continue;  // the first triangle only (the second's map differs)
      CHECK(glm::length(glm::dvec2(dpdu) - a[0]) < 1e-4);
      CHECK(glm::length(glm::dvec2(dpdv) - a[1]) < 1e-4);
      CHECK(std::abs(dpdu.z) < 1e-5f);
    }
    ++checked;
  }
  CHECK(checked > 100);
}
