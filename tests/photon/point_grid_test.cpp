// The irradiance points' grid against a brute-force scan: every answer it gives is an accepted
// point within twice the true nearest distance, and it answers most queries on the surfaces.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <cmath>
#include "core/rng.h"
#include "photon/point_grid.h"

using namespace caustica;

namespace {
struct Points {
  std::vector<Vec3> p, n;
};

// Points on the six inner walls of a box [0, 100]^3 (normals pointing inside), denser on the
// floor, as photons fall in a room; plus a small cluster in the middle with random normals.
Points room(size_t per_wall, uint64_t seed) {
  Rng rng(seed);
  Points pts;
  for (int wall = 0; wall < 6; ++wall) {
    const int axis = wall / 2;
    const bool high = wall % 2 == 1;
    const size_t count = wall == 2 ? 4 * per_wall : per_wall;  // y = 0: the floor
    for (size_t i = 0; i < count; ++i) {
      Vec3 p(100.0f * rng.next_float(), 100.0f * rng.next_float(), 100.0f * rng.next_float());
      p[axis] = high ? 100.0f : 0.0f;
      Vec3 n(0.0f);
      n[axis] = high ? -1.0f : 1.0f;
      pts.p.push_back(p);
      pts.n.push_back(n);
    }
  }
  for (int i = 0; i < 200; ++i) {
    pts.p.push_back(Vec3(50.0f) + 3.0f * Vec3(rng.next_float(), rng.next_float(), rng.next_float()));
    const Vec3 n(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f);
    pts.n.push_back(glm::normalize(n + Vec3(1e-3f)));
  }
  return pts;
}

bool agrees(const Vec3& a, const Vec3& b) { return glm::dot(a, b) > 0.9f; }

// The nearest accepted point within max_radius by a full scan: its squared distance, or -1.
float brute_nearest2(const Points& pts, const Vec3& q, const Vec3& side, float max_radius) {
  float best = max_radius * max_radius;
  bool found = false;
  for (size_t i = 0; i < pts.p.size(); ++i) {
    const Vec3 d = pts.p[i] - q;
    const float d2 = glm::dot(d, d);
    if (d2 < best && agrees(pts.n[i], side)) {
      best = d2;
      found = true;
    }
  }
  return found ? best : -1.0f;
}
}  // namespace

TEST_CASE("point grid: answers agree with a brute-force scan", "[photon][grid]" TIER_UNIT) {
  const Points pts = room(2000, 3);
  PointGrid grid;
  grid.build(pts.p, pts.n);
  REQUIRE(grid.size() == pts.p.size());
  REQUIRE(grid.cell_size() > 0.0f);
  Rng rng(9);
  int decided = 0, on_surface = 0, none = 0, with_rejected = 0;
  for (int k = 0; k < 4000; ++k) {
    // Mostly points on a wall (a gather ray's hit), some anywhere in and around the box.
    const int wall = int(rng.next_u32() % 6);
    const int axis = wall / 2;
    Vec3 q(110.0f * rng.next_float() - 5.0f, 110.0f * rng.next_float() - 5.0f, 110.0f * rng.next_float() - 5.0f);
    Vec3 side(0.0f);
    side[axis] = wall % 2 ? -1.0f : 1.0f;
    const bool surface = k % 4 != 0;
    if (surface) q[axis] = wall % 2 ? 100.0f : 0.0f;
    // A third of them near an edge, where the other wall's points (rejected) lie nearer.
    if (surface && k % 3 == 0) q[(axis + 1) % 3] = 3.0f * rng.next_float();
    // Radii from so small that nothing is found to wider than the block, some near a cell.
    const float radii[4] = {0.5f, 0.6f * grid.cell_size(), 1.2f * grid.cell_size(), 30.0f};
    const float max_radius = radii[k % 4 == 1 ? k / 4 % 3 : 3];
    const int64_t g = grid.nearest(q, max_radius, [&](const Vec3& n) { return agrees(n, side); });
    const float truth2 = brute_nearest2(pts, q, side, max_radius);
    if (g >= 0) {
      REQUIRE(size_t(g) < pts.p.size());
      CHECK(agrees(pts.n[size_t(g)], side));
      const Vec3 d = pts.p[size_t(g)] - q;
      REQUIRE(truth2 >= 0.0f);
      CHECK(glm::dot(d, d) < max_radius * max_radius);
      CHECK(std::sqrt(glm::dot(d, d)) <= 2.0f * std::sqrt(truth2) + 1e-4f);
      // Where only rejected points lie nearer, there are fewer than 8 of them.
      const float g2 = glm::dot(d, d);
      int nearer = 0, nearer_accepted = 0;
      for (size_t i = 0; i < pts.p.size(); ++i) {
        const Vec3 di = pts.p[i] - q;
        if (glm::dot(di, di) >= g2) continue;
        ++nearer;
        nearer_accepted += agrees(pts.n[i], side) ? 1 : 0;
      }
      if (nearer > 0 && nearer_accepted == 0) {
        CHECK(nearer < 8);
        ++with_rejected;
      }
    } else if (g == PointGrid::kNone) {
      CHECK(truth2 < 0.0f);
      ++none;
    } else {
      CHECK(g == PointGrid::kUndecided);
    }
    if (surface && k % 3 != 0 && max_radius == 30.0f) {  // on a wall, away from its edges
      ++on_surface;
      decided += g >= 0 ? 1 : 0;
    }
  }
  // The grid is what answers: most queries on a wall with a wide radius end there. (The cells
  // follow the dense floor; on the walls, at a quarter of its density, the nearest point is
  // farther than a cell for about one query in five.)
  CHECK(decided > 0.7 * on_surface);
  CHECK(none > 0);
  CHECK(with_rejected > 0);  // the edges were reached
}

TEST_CASE("point grid: empty, single and coincident points, queries far away", "[photon][grid]" TIER_UNIT) {
  PointGrid empty;
  empty.build({}, {});
  CHECK(empty.nearest(Vec3(0.0f), 1.0f, [](const Vec3&) { return true; }) == PointGrid::kNone);

  PointGrid one;
  one.build({Vec3(1, 2, 3)}, {Vec3(0, 0, 1)});
  const auto any = [](const Vec3&) { return true; };
  CHECK(one.nearest(Vec3(1, 2, 3.1f), 1.0f, any) == 0);
  CHECK(one.nearest(Vec3(1, 2, 3.1f), 1.0f, [](const Vec3& n) { return n.z < 0.0f; }) != 0);

  // All at one place: a zero extent still gives a usable cell.
  PointGrid same;
  same.build(std::vector<Vec3>(50, Vec3(5.0f)), std::vector<Vec3>(50, Vec3(0, 1, 0)));
  CHECK(same.cell_size() > 0.0f);
  const int64_t s = same.nearest(Vec3(5.0f, 5.001f, 5.0f), 1.0f, any);
  CHECK((s == 0 || s == PointGrid::kUndecided));  // the lowest index among equals, if decided

  // Far outside the points' box, and not a number: left to the caller, never wrong.
  const Points pts = room(200, 4);
  PointGrid grid;
  grid.build(pts.p, pts.n);
  CHECK(grid.nearest(Vec3(1e6f, 0.0f, 0.0f), 10.0f, any) == PointGrid::kUndecided);
  CHECK(grid.nearest(Vec3(std::nanf(""), 0.0f, 0.0f), 10.0f, any) == PointGrid::kUndecided);
}

TEST_CASE("point grid: an accepted point behind 8 rejected ones is left to the caller", "[photon][grid]" TIER_UNIT) {
  // A sheet of points facing +z, and at q a cluster facing -z (rejected by the query's side).
  Rng rng(2);
  std::vector<Vec3> p, n;
  for (int i = 0; i < 400; ++i) {
    p.push_back(Vec3(20.0f * rng.next_float(), 20.0f * rng.next_float(), 0.0f));
    n.push_back(Vec3(0, 0, 1));
  }
  const Vec3 q(10.0f, 10.0f, 0.01f);
  const auto up = [](const Vec3& v) { return v.z > 0.0f; };
  for (int cluster : {3, 10}) {
    std::vector<Vec3> cp = p, cn = n;
    for (int i = 0; i < cluster; ++i) {
      cp.push_back(q + Vec3(0.001f * float(i), 0.0f, 0.0f));
      cn.push_back(Vec3(0, 0, -1));
    }
    PointGrid grid;
    grid.build(cp, cn);
    const int64_t g = grid.nearest(q, 30.0f, up);
    if (cluster >= 8) {
      CHECK(g == PointGrid::kUndecided);
    } else if (g >= 0) {
      CHECK(up(cn[size_t(g)]));  // then the nearest accepted point
      float best = kInfinity;
      for (size_t i = 0; i < cp.size(); ++i) {
        if (up(cn[i])) best = std::min(best, glm::length(cp[i] - q));
      }
      CHECK(glm::length(cp[size_t(g)] - q) == Approx(best));
    }
  }
}

TEST_CASE("point grid: points that are not finite are left out", "[photon][grid]" TIER_UNIT) {
  std::vector<Vec3> p{Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), Vec3(std::nanf(""), 0.0f, 0.0f), Vec3(kInfinity)};
  std::vector<Vec3> n(4, Vec3(0, 0, 1));
  PointGrid grid;
  grid.build(p, n);
  CHECK(grid.size() == 2);
  const int64_t g = grid.nearest(Vec3(0.9f, 0.0f, 0.0f), 5.0f, [](const Vec3&) { return true; });
  CHECK((g == 1 || g == PointGrid::kUndecided));
}
