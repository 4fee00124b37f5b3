// Round linear curves: random rays through both backends against a brute-force march of the
// swept sphere's distance; backfaces culled.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <algorithm>
#include "core/accel.h"
#include "core/error.h"
#include "core/sampling.h"
#include "support/random.h"

using namespace caustica;
using test::random_in_box;

namespace {
// Distance from p to the sphere swept from (a, ra) to (b, rb): the least over s of |p - c(s)| -
// r(s), a convex function of s, by ternary search (independent of the closed form under test).
double swept_distance(const Vec3& p, const Primitive& c) {
  auto g = [&](double s) {
    const glm::dvec3 centre = glm::dvec3(c.p0) + s * (glm::dvec3(c.p1) - glm::dvec3(c.p0));
    return glm::length(glm::dvec3(p) - centre) - (c.p2.x + s * (double(c.p2.y) - c.p2.x));
  };
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 80; ++i) {
    const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
    if (g(m1) < g(m2)) hi = m2;
    else lo = m1;
  }
  return g(0.5 * (lo + hi));
}

// The first entry into any of the curves along the ray: a march, then bisection.
bool brute_force(const std::vector<Primitive>& curves, const Ray& ray, float t_end, float& t) {
  auto f = [&](double tt) {
    double d = kInfinity;
    for (const Primitive& c : curves) d = std::min(d, swept_distance(ray.at(float(tt)), c));
    return d;
  };
  if (f(0.0) < 0.0) return false;  // starts inside: culled
  const int steps = 1500;
  double prev = 0.0;
  for (int i = 1; i <= steps; ++i) {
    const double tt = t_end * i / steps;
    if (f(tt) < 0.0) {
      double lo = prev, hi = tt;
      for (int k = 0; k < 40; ++k) {
        const double mid = 0.5 * (lo + hi);
        (f(mid) < 0.0 ? hi : lo) = mid;
      }
      t = float(0.5 * (lo + hi));
      return true;
    }
    prev = tt;
  }
  return false;
}
std::vector<std::unique_ptr<Accelerator>> both_backends(const std::vector<Primitive>& prims) {
  std::vector<std::unique_ptr<Accelerator>> accels;
  accels.push_back(make_accelerator(AccelKind::Bvh, prims));
#ifdef CAUSTICA_EMBREE
  accels.push_back(make_accelerator(AccelKind::Embree, prims));
#endif
  return accels;
}

Bounds bounds_of(const std::vector<Primitive>& prims) {
  Bounds box;
  for (const Primitive& c : prims) box.extend(c.bounds());
  return box;
}
}  // namespace

TEST_CASE("linearcurve: random rays hit round linear curves where a brute-force march does, in both backends",
          "[curve][accel]" TIER_UNIT) {
  Rng rng(20261207);
  for (int scene = 0; scene < 4; ++scene) {
    // A wavy chain of segments with radii from thin to thick, a few of them tapering fast.
    std::vector<Primitive> curves;
    Vec3 p = random_in_box(rng, -1.0f, 1.0f);
    float r = 0.05f + 0.3f * rng.next_float();
    for (int i = 0; i < 6; ++i) {
      const Vec3 q = p + 1.5f * glm::normalize(random_in_box(rng, -1.0f, 1.0f));
      const float rq = 0.02f + 0.4f * rng.next_float();
      curves.push_back(Primitive::linear_curve(p, r, q, rq, uint32_t(i), 6));
      p = q, r = rq;
    }
    const auto accels = both_backends(curves);
    const Bounds box = bounds_of(curves);
    int hits = 0;
    for (int i = 0; i < 60; ++i) {
      const Vec3 target = random_in_box(rng, 0.0f, 1.0f) * box.extent() + box.lo;
      const Vec3 o = target + 6.0f * sample_uniform_sphere(Vec2(rng.next_float(), rng.next_float()));
      const Ray ray{o, glm::normalize(target - o), kInfinity};
      float t_ref = 0.0f;
      const bool ref = brute_force(curves, ray, 14.0f, t_ref);
      for (const auto& accel : accels) {
        Hit h;
        const bool hit = accel->intersect(ray, h);
        INFO("scene " << scene << " ray " << i << " " << accel->name() << ": reference " << ref << " at " << t_ref
                      << ", hit " << hit << " at " << h.t);
        // The march resolves 14 / 1500 along the ray: a grazing ray may slip between its steps.
        if (hit != ref) {
          float closest = kInfinity;
          for (int k = 0; k <= 1500; ++k) {
            double d = kInfinity;
            for (const Primitive& c : curves) d = std::min(d, swept_distance(ray.at(14.0f * k / 1500), c));
            closest = std::min(closest, float(d));
          }
          CHECK(closest < 0.01f);  // a grazing ray: the surface within 1 % of a step
          continue;
        }
        if (hit) CHECK(h.t == Approx(t_ref).epsilon(1e-4).margin(1e-4));
      }
      if (ref) ++hits;
    }
    CHECK(hits > 10);
  }
}

TEST_CASE("linearcurve: a ray from inside a curve does not hit it (culled backfaces, as Embree and Mitsuba)", "[curve][accel]" TIER_UNIT) {
  const std::vector<Primitive> curves = {Primitive::linear_curve(Vec3(0, 0, 0), 0.5f, Vec3(3, 0, 0), 0.2f, 0, 1)};
  for (AccelKind kind : {AccelKind::Bvh, AccelKind::Embree}) {
    if (choose_accel(kind) != kind) continue;
    const auto accel = make_accelerator(kind, curves);
    INFO(accel->name());
    Hit h;
    CHECK_FALSE(accel->intersect(Ray{Vec3(1, 0, 0), Vec3(0, 1, 0), kInfinity}, h));
    // From outside: the radius there is 0.5 + (1/3) (0.2 - 0.5) = 0.4 (slightly more on the
    // tangent cone, whose touching circles lie off the end points).
    REQUIRE(accel->intersect(Ray{Vec3(1, 5, 0), Vec3(0, -1, 0), kInfinity}, h));
    CHECK(5.0f - h.t == Approx(0.4f).margin(0.01));
    // The end cap: parallel to the axis, 0.1 off it, into the sphere at a (a ray exactly on
    // the axis slips through Embree 3's curve test).
    REQUIRE(accel->intersect(Ray{Vec3(-5, 0.1f, 0), Vec3(1, 0, 0), kInfinity}, h));
    CHECK(h.t == Approx(5.0f - std::sqrt(0.24f)).margin(1e-5));
    // Shadow rays alike: from inside, nothing; from outside, the curve.
    CHECK_FALSE(accel->occluded(Ray{Vec3(1, 0, 0), Vec3(0, 1, 0), 10.0f}));
    CHECK(accel->occluded(Ray{Vec3(1, 5, 0), Vec3(0, -1, 0), 10.0f}));
  }
}


namespace {
// Distance from p to the sweep of a B-spline segment: the least over u of |p - c(u)| - r(u),
// by dense samples and a local ternary search (independent of the Newton test under test).
double spline_distance(const Vec3& p, const glm::vec4 cp[4], double* u_closest = nullptr) {
  auto g = [&](double u) {
    const glm::vec4 c = bspline_point(cp, float(u));
    return double(glm::length(p - Vec3(c))) - c.w;
  };
  int best = 0;
  double best_g = kInfinity;
  for (int i = 0; i <= 200; ++i) {
    const double gi = g(i / 200.0);
    if (gi < best_g) best_g = gi, best = i;
  }
  double lo = std::max(0.0, (best - 1) / 200.0), hi = std::min(1.0, (best + 1) / 200.0);
  for (int i = 0; i < 40; ++i) {
    const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
    if (g(m1) < g(m2)) hi = m2;
    else lo = m1;
  }
  if (u_closest) *u_closest = 0.5 * (lo + hi);
  return g(0.5 * (lo + hi));
}
}  // namespace

TEST_CASE("bsplinecurve: random rays hit round B-spline curves where a brute-force march does, in both backends",
          "[curve][accel]" TIER_UNIT) {
  Rng rng(20261208);
  for (int scene = 0; scene < 3; ++scene) {
    // One curve of 7 control points (4 segments), bending, radii thin to thick.
    std::vector<glm::vec4> points;
    Vec3 p = random_in_box(rng, -1.0f, 1.0f);
    for (int i = 0; i < 7; ++i) {
      points.push_back(glm::vec4(p, 0.05f + 0.2f * rng.next_float()));
      p += 0.8f * glm::normalize(random_in_box(rng, -1.0f, 1.0f));
    }
    std::vector<glm::vec4> segments;
    for (int s = 0; s + 3 < 7; ++s) segments.insert(segments.end(), points.begin() + s, points.begin() + s + 4);
    std::vector<Primitive> curves;
    for (uint32_t s = 0; s < 4; ++s) curves.push_back(Primitive::bspline_curve(segments.data() + 4 * s, s, 4));
    const auto accels = both_backends(curves);
    // The sweep is open at the curve's ends (as Embree's): rays whose first entry lies near
    // an end (where they may pass into the tube without crossing its surface) are left out.
    bool near_end = false;
    auto distance = [&](const Vec3& x) {
      double d = kInfinity;
      for (uint32_t s = 0; s < 4; ++s) {
        double u;
        const double ds = spline_distance(x, segments.data() + 4 * s, &u);
        if (ds < d) d = ds, near_end = (s == 0 && u < 0.3) || (s == 3 && u > 0.7);
      }
      return d;
    };
    int hits = 0, compared = 0;
    for (int i = 0; i < 50; ++i) {
      // Aimed near the curve: a point of a random segment, moved by up to 0.3.
      const uint32_t seg = rng.next_u32() % 4;
      near_end = false;
      const Vec3 target = Vec3(bspline_point(segments.data() + 4 * seg, rng.next_float())) + 0.3f * random_in_box(rng, -1.0f, 1.0f);
      const Vec3 o = target + 6.0f * sample_uniform_sphere(Vec2(rng.next_float(), rng.next_float()));
      const Ray ray{o, glm::normalize(target - o), kInfinity};
      // The march: the first point inside the sweep (every segment's u in [0, 1]: open ends).
      const int steps = 1200;
      float t_ref = -1.0f, closest = kInfinity;
      for (int k = 1; k <= steps && t_ref < 0.0f; ++k) {
        const double dk = distance(ray.at(12.0f * k / steps));
        closest = std::min(closest, float(dk));
        if (dk < 0.0) {
          double lo = 12.0 * (k - 1) / steps, hi = 12.0 * k / steps;
          for (int b = 0; b < 30; ++b) {
            const double mid = 0.5 * (lo + hi);
            (distance(ray.at(float(mid))) < 0.0 ? hi : lo) = mid;
          }
          t_ref = float(0.5 * (lo + hi));
        }
      }
      if (t_ref > 0.0f) {
        distance(ray.at(t_ref));
        if (near_end) continue;
      }
      const bool ref = t_ref > 0.0f;
      for (const auto& accel : accels) {
        Hit h;
        const bool hit = accel->intersect(ray, h);
        INFO("scene " << scene << " ray " << i << " " << accel->name() << ": reference " << ref << " at " << t_ref
                      << ", hit " << hit << " at " << h.t << ", closest approach " << closest);
        if (hit != ref) {
          // Only a ray grazing the surface (or an open end) may differ.
          CHECK(std::abs(closest) < 0.02f);
          continue;
        }
        if (hit) {
          // A first entry that is a shallow graze (the sweep nowhere 1 % deep between the two
          // distances) may be passed over; elsewhere our BVH finds the sweep to 1e-3 and Embree's
          // round B-spline test, which approximates the sweep, to 0.3 % of t.
          float deepest = 0.0f;
          for (int k = 0; k <= 40; ++k) {
            const float tk = std::min(t_ref, h.t) + std::abs(h.t - t_ref) * float(k) / 40.0f;
            deepest = std::min(deepest, float(distance(ray.at(tk))));
          }
          if (std::abs(h.t - t_ref) > 0.01f && deepest > -0.01f) continue;
          const double tolerance = std::string(accel->name()) == "embree" ? 3e-3 : 1e-3;
          CHECK(h.t == Approx(t_ref).epsilon(tolerance).margin(1e-3));
          ++compared;
        }
      }
      if (ref) ++hits;
    }
    CHECK(hits > 10);
    CHECK(compared > int(accels.size()) * hits - 6);  // (a few grazing rays may differ)
  }
}
