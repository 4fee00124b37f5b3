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
