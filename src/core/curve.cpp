// Round linear curve segments: see curve.h. The segment is the convex hull of its two end
// spheres: in the plane through the axis, a circle of radius R(s) = ra + s dr at axial position
// s L has the envelope rho L' = dr z + L ra (z along the axis from a, rho from it, L' =
// sqrt(L^2 - dr^2)), touched by circle s at z = s L - dr R(s) / L. A ray enters the hull at the
// first of its entries into the cone between the touching circles and into the two spheres.
#include "core/curve.h"
#include <algorithm>
#include <cmath>

namespace caustica {
namespace {
using D3 = glm::dvec3;

// The first root of the ray (o, unit d) with a sphere, or +inf.
double sphere_entry(const D3& o, const D3& d, const D3& c, double r) {
  const D3 oc = o - c;
  const double b = glm::dot(oc, d), cc = glm::dot(oc, oc) - r * r;
  const double disc = b * b - cc;
  if (disc < 0.0) return kInfinity;
  return -b - std::sqrt(disc);
}

// The swept sphere's parameter at a point q (relative to a) and the signed distance to it.
double parameter(const D3& q, const D3& ba, double ra, double dr, double* distance) {
  const double m0 = glm::dot(ba, ba), L = std::sqrt(m0);
  double s;
  if (!(m0 > dr * dr)) {
    s = dr > 0.0 ? 1.0 : 0.0;  // one sphere holds the other: the larger is the shape
  } else {
    const double alpha = glm::dot(q, ba), rho = std::sqrt(std::max(0.0, glm::dot(q, q) - alpha * alpha / m0));
    s = std::clamp(alpha / m0 + dr * rho / (L * std::sqrt(m0 - dr * dr)), 0.0, 1.0);
  }
  if (distance) *distance = glm::length(q - s * ba) - (ra + s * dr);
  return s;
}
}  // namespace

bool intersect_round_cone(const Ray& ray, const Vec3& a_f, float ra_f, const Vec3& b_f, float rb_f, float tmax, float& t_hit) {
  const D3 o(ray.origin), d(ray.dir), a(a_f), b(b_f);
  const double ra = ra_f, rb = rb_f, dr = rb - ra;
  const D3 ba = b - a, oa = o - a;
  // Backfaces are culled: a ray from inside the curve does not hit it.
  double inside;
  parameter(oa, ba, ra, dr, &inside);
  if (inside < 0.0) return false;
  double best = std::min(sphere_entry(o, d, a, ra), sphere_entry(o, d, b, rb));
  const double m0 = glm::dot(ba, ba);
  if (m0 > dr * dr) {
    // (|q|^2 m0 - alpha^2)(m0 - dr^2) = (dr alpha + m0 ra)^2 along q = oa + t d, alpha = q . ba.
    const double m1 = glm::dot(ba, oa), m2 = glm::dot(ba, d), m3 = glm::dot(d, oa), m5 = glm::dot(oa, oa);
    const double k = m0 - dr * dr, e = dr * m1 + m0 * ra;
    const double A = (m0 - m2 * m2) * k - dr * dr * m2 * m2;
    const double B = (m0 * m3 - m1 * m2) * k - dr * m2 * e;
    const double C = (m0 * m5 - m1 * m1) * k - e * e;
    const double disc = B * B - A * C;
    if (A != 0.0 && disc >= 0.0) {
      const double root = std::sqrt(disc);
      for (double t : {(-B - root) / A, (-B + root) / A}) {
        // On the part of the cone between the touching circles (which is also its right nappe).
        const double alpha = m1 + t * m2;
        if (alpha >= -dr * ra && alpha <= m0 - dr * rb && t < best) best = t;
      }
    }
  }
  if (!(best > 0.0) || !(best < double(tmax))) return false;
  t_hit = float(best);
  return t_hit > 0.0f && t_hit < tmax;
}

float round_cone_parameter(const Vec3& p, const Vec3& a, float ra, const Vec3& b, float rb) {
  return float(parameter(D3(p) - D3(a), D3(b) - D3(a), ra, double(rb) - ra, nullptr));
}

}  // namespace caustica
