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

namespace caustica {
namespace {
using D4 = glm::dvec4;

// The uniform cubic B-spline's basis at u, and its first and second derivatives.
void basis(double u, double b[4], double d1[4], double d2[4]) {
  const double v = 1.0 - u;
  b[0] = v * v * v / 6.0, b[1] = (3.0 * u * u * u - 6.0 * u * u + 4.0) / 6.0;
  b[2] = (-3.0 * u * u * u + 3.0 * u * u + 3.0 * u + 1.0) / 6.0, b[3] = u * u * u / 6.0;
  d1[0] = -0.5 * v * v, d1[1] = 0.5 * (3.0 * u * u - 4.0 * u), d1[2] = 0.5 * (-3.0 * u * u + 2.0 * u + 1.0), d1[3] = 0.5 * u * u;
  d2[0] = v, d2[1] = 3.0 * u - 2.0, d2[2] = 1.0 - 3.0 * u, d2[3] = u;
}

D4 combine(const glm::vec4 cp[4], const double w[4]) {
  D4 s(0.0);
  for (int i = 0; i < 4; ++i) s += w[i] * D4(cp[i]);
  return s;
}

// The first entry of the ray into a round linear piece, caps included, inside or not (a start
// for Newton's method), or +inf.
double piece_entry(const D3& o, const D3& d, const D3& a, double ra, const D3& b, double rb) {
  double best = std::min(sphere_entry(o, d, a, ra), sphere_entry(o, d, b, rb));
  const D3 ba = b - a, oa = o - a;
  const double dr = rb - ra, m0 = glm::dot(ba, ba);
  if (m0 > dr * dr) {
    const double m1 = glm::dot(ba, oa), m2 = glm::dot(ba, d), m3 = glm::dot(d, oa), m5 = glm::dot(oa, oa);
    const double k = m0 - dr * dr, e = dr * m1 + m0 * ra;
    const double A = (m0 - m2 * m2) * k - dr * dr * m2 * m2, B = (m0 * m3 - m1 * m2) * k - dr * m2 * e;
    const double C = (m0 * m5 - m1 * m1) * k - e * e, disc = B * B - A * C;
    if (A != 0.0 && disc >= 0.0) {
      const double root = std::sqrt(disc);
      for (double t : {(-B - root) / A, (-B + root) / A}) {
        const double alpha = m1 + t * m2;
        if (alpha >= -dr * ra && alpha <= m0 - dr * rb && t < best) best = t;
      }
    }
  }
  return best;
}
}  // namespace

glm::vec4 bspline_point(const glm::vec4 cp[4], float u) {
  double b[4], d1[4], d2[4];
  basis(u, b, d1, d2);
  return glm::vec4(combine(cp, b));
}

glm::vec4 bspline_tangent(const glm::vec4 cp[4], float u) {
  double b[4], d1[4], d2[4];
  basis(u, b, d1, d2);
  return glm::vec4(combine(cp, d1));
}

bool intersect_bspline(const Ray& ray, const glm::vec4 cp[4], float tmax, float& t_hit, float* u_hit) {
  constexpr int kPieces = 16;
  const D3 o(ray.origin), d(ray.dir);
  double best = kInfinity, best_u = 0.0;
  double b0[4], b1[4], b2[4];
  basis(0.0, b0, b1, b2);
  D4 prev = combine(cp, b0);
  for (int k = 0; k < kPieces; ++k) {
    double b[4], d1[4], d2[4];
    basis(double(k + 1) / kPieces, b, d1, d2);
    const D4 next = combine(cp, b);
    const double t0 = piece_entry(o, d, D3(prev), prev.w, D3(next), next.w);
    const D3 a(prev), e(next);
    prev = next;
    if (!(t0 < kInfinity) || t0 < -1e30) continue;
    // Newton's method on F1 = |x - c|^2 - r^2, F2 = (x - c) . c' + r r' (the envelope), x = o + t d.
    const D3 x0 = o + t0 * d;
    double s = 0.0;
    {
      const D3 ea = e - a;
      const double len2 = glm::dot(ea, ea);
      s = len2 > 0.0 ? std::clamp(glm::dot(x0 - a, ea) / len2, 0.0, 1.0) : 0.5;
    }
    double t = t0, u = (k + s) / kPieces;
    bool converged = false;
    for (int it = 0; it < 24; ++it) {
      double bb[4], b1[4], b2[4];
      basis(u, bb, b1, b2);
      const D4 c = combine(cp, bb), c1 = combine(cp, b1), c2 = combine(cp, b2);
      const D3 w = o + t * d - D3(c), T(c1), A(c2);
      const double F1 = glm::dot(w, w) - c.w * c.w, F2 = glm::dot(w, T) + c.w * c1.w;
      const double j11 = 2.0 * glm::dot(w, d), j12 = -2.0 * F2;
      const double j21 = glm::dot(d, T), j22 = -glm::dot(T, T) + glm::dot(w, A) + c1.w * c1.w + c.w * c2.w;
      const double det = j11 * j22 - j12 * j21;
      if (det == 0.0 || !std::isfinite(det)) break;
      const double dt = (-F1 * j22 + F2 * j12) / det, du = (-j11 * F2 + j21 * F1) / det;
      t += dt;
      u = std::clamp(u + du, -0.05, 1.05);
      if (std::abs(dt) <= 1e-10 * (1.0 + std::abs(t)) && std::abs(du) <= 1e-10) {
        converged = true;
        break;
      }
    }
    if (!converged || u < 0.0 || u > 1.0 || !(t > 0.0) || !(t < best)) continue;
    // An entry: the surface's normal (x - c(u)) faces the ray.
    double bb[4], b1[4], b2[4];
    basis(u, bb, b1, b2);
    if (glm::dot(o + t * d - D3(combine(cp, bb)), d) >= 0.0) continue;
    best = t, best_u = u;
  }
  if (!(best < double(tmax))) return false;
  t_hit = float(best);
  if (u_hit) *u_hit = float(best_u);
  return t_hit > 0.0f && t_hit < tmax;
}

float bspline_parameter(const Vec3& p_f, const glm::vec4 cp[4]) {
  const D3 p(p_f);
  auto g = [&](double u) {
    double b[4], d1[4], d2[4];
    basis(u, b, d1, d2);
    const D4 c = combine(cp, b);
    return glm::length(p - D3(c)) - c.w;
  };
  constexpr int kSamples = 64;
  int best = 0;
  double best_g = kInfinity;
  for (int i = 0; i <= kSamples; ++i) {
    const double gi = g(double(i) / kSamples);
    if (gi < best_g) best_g = gi, best = i;
  }
  double lo = std::max(0.0, double(best - 1) / kSamples), hi = std::min(1.0, double(best + 1) / kSamples);
  for (int i = 0; i < 60; ++i) {
    const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
    if (g(m1) < g(m2)) hi = m2;
    else lo = m1;
  }
  return float(0.5 * (lo + hi));
}

}  // namespace caustica
