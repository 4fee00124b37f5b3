// Round linear curves (Mitsuba 3's `linearcurve`, Embree's RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE):
// a segment from a (radius ra) to b (radius rb) is the sphere swept along it, the cone that
// touches both end spheres plus the spheres. Seen from outside, a chain of segments is the union
// of these; as in Embree and Mitsuba, a ray that starts inside a curve does not hit it
// (backfaces are culled).
#pragma once
#include "core/math.h"

namespace caustica {

// The first entry into the swept sphere along `ray` (unit direction) at 0 < t < tmax.
bool intersect_round_cone(const Ray& ray, const Vec3& a, float ra, const Vec3& b, float rb, float tmax, float& t);

// For a point p on the segment's surface: the parameter s in [0, 1] of the sphere it lies on
// (centre a + s (b - a), radius ra + s (rb - ra)); the outward normal is p minus that centre.
float round_cone_parameter(const Vec3& p, const Vec3& a, float ra, const Vec3& b, float rb);

}  // namespace caustica

namespace caustica {

// Round cubic B-spline curves (Mitsuba 3's `bsplinecurve`, Embree's
// RTC_GEOMETRY_TYPE_ROUND_BSPLINE_CURVE): a segment of four control points cp (x, y, z, radius)
// is the envelope of the spheres centred on the uniform cubic B-spline c(u) with radius r(u)
// (the same spline of the radii), u in [0, 1]; as in Embree, open at its ends (a curve's segments
// join smoothly) and culled from inside. The test starts Newton's method on (t, u) from the hits
// of 16 round linear pieces along the segment, so a ray grazing the sweep within the pieces'
// sagitta of its silhouette may miss it.
glm::vec4 bspline_point(const glm::vec4 cp[4], float u);    // (c(u), r(u))
glm::vec4 bspline_tangent(const glm::vec4 cp[4], float u);  // (c'(u), r'(u))
bool intersect_bspline(const Ray& ray, const glm::vec4 cp[4], float tmax, float& t, float* u_hit = nullptr);
// The u of the sphere on whose envelope a point of the surface lies.
float bspline_parameter(const Vec3& p, const glm::vec4 cp[4]);

}  // namespace caustica
