// SDF grids: see sdf_grid.h.
#include "core/sdf_grid.h"
#include <algorithm>
#include <cmath>
#include "core/shape.h"

namespace caustica {
namespace {

// The trilinear interpolant of corner values c (indexed x + 2y + 4z) as a polynomial:
// a0 + a1 x + a2 y + a3 z + a4 xy + a5 yz + a6 xz + a7 xyz.
struct Trilinear {
  double a[8];
  explicit Trilinear(const float c[8]) {
    a[0] = c[0];
    a[1] = double(c[1]) - c[0];
    a[2] = double(c[2]) - c[0];
    a[3] = double(c[4]) - c[0];
    a[4] = double(c[3]) - c[1] - c[2] + c[0];
    a[5] = double(c[6]) - c[2] - c[4] + c[0];
    a[6] = double(c[5]) - c[1] - c[4] + c[0];
    a[7] = double(c[7]) - c[3] - c[5] - c[6] + c[1] + c[2] + c[4] - c[0];
  }
  double operator()(const glm::dvec3& q) const {
    const double x = q.x, y = q.y, z = q.z;
    return a[0] + a[1] * x + a[2] * y + a[3] * z + a[4] * x * y + a[5] * y * z + a[6] * x * z + a[7] * x * y * z;
  }
  glm::dvec3 gradient(const glm::dvec3& q) const {
    const double x = q.x, y = q.y, z = q.z;
    return {a[1] + a[4] * y + a[6] * z + a[7] * y * z, a[2] + a[4] * x + a[5] * z + a[7] * x * z,
            a[3] + a[5] * y + a[6] * x + a[7] * x * y};
  }
};

// The interpolant on corner values by lerps: exactly the corner value at a corner and exactly
// the face's bilinear interpolant on a face, so that two voxels sharing a face agree on it
// bit for bit (and a crossing on the face is found by one of them).
double lerp3(const float c[8], const glm::dvec3& q) {
  auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
  const double x00 = lerp(c[0], c[1], q.x), x10 = lerp(c[2], c[3], q.x);
  const double x01 = lerp(c[4], c[5], q.x), x11 = lerp(c[6], c[7], q.x);
  return lerp(lerp(x00, x10, q.y), lerp(x01, x11, q.y), q.z);
}

// Roots of a s^2 + b s + c in increasing order; the count (0, 1 or 2).
int quadratic_roots(double a, double b, double c, double r[2]) {
  if (a == 0.0) {
    if (b == 0.0) return 0;
    r[0] = -c / b;
    return 1;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return 0;
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  r[0] = q / a;
  r[1] = q != 0.0 ? c / q : r[0];
  if (r[0] > r[1]) std::swap(r[0], r[1]);
  return 2;
}
}  // namespace

SdfGrid::SdfGrid(int nx, int ny, int nz, std::vector<float> values, const glm::mat4& to_world, Normals normals)
    : n_{nx, ny, nz}, values_(std::move(values)), to_world_(to_world), normals_(normals) {
  to_local_ = glm::inverse(to_world_);
  normal_matrix_ = glm::transpose(glm::dmat3(to_local_));
}

std::vector<uint32_t> SdfGrid::surface_voxels() const {
  std::vector<uint32_t> out;
  for (int z = 0; z + 1 < n_[2]; ++z) {
    for (int y = 0; y + 1 < n_[1]; ++y) {
      for (int x = 0; x + 1 < n_[0]; ++x) {
        const uint32_t v = uint32_t((size_t(z) * size_t(n_[1]) + size_t(y)) * size_t(n_[0]) + size_t(x));
        float c[8];
        corners(v, c);
        const float lo = *std::min_element(c, c + 8), hi = *std::max_element(c, c + 8);
        if (lo <= 0.0f && hi >= 0.0f) out.push_back(v);
      }
    }
  }
  return out;
}

void SdfGrid::corners(uint32_t voxel, float c[8]) const {
  const size_t nx = size_t(n_[0]), nxy = nx * size_t(n_[1]);
  for (int i = 0; i < 8; ++i) c[i] = values_[voxel + size_t(i & 1) + size_t((i >> 1) & 1) * nx + size_t(i >> 2) * nxy];
}

Bounds SdfGrid::voxel_bounds(uint32_t voxel) const {
  const int x = int(voxel % uint32_t(n_[0])), y = int(voxel / uint32_t(n_[0]) % uint32_t(n_[1]));
  const int z = int(voxel / uint32_t(n_[0]) / uint32_t(n_[1]));
  Bounds b;
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 local(double(x + (i & 1)) / (n_[0] - 1), double(y + ((i >> 1) & 1)) / (n_[1] - 1),
                           double(z + (i >> 2)) / (n_[2] - 1));
    b.extend(Vec3(glm::dvec3(to_world_ * glm::dvec4(local, 1.0))));
  }
  // A margin for the rounding of the corners to float: the accelerators test the box first.
  const Vec3 pad = 1e-5f * b.extent() + 1e-7f * glm::max(glm::abs(b.lo), glm::abs(b.hi));
  b.lo -= pad;
  b.hi += pad;
  return b;
}

Vec3 SdfGrid::to_voxel(const Vec3& p, uint32_t voxel) const {
  const glm::dvec3 local(to_local_ * glm::dvec4(glm::dvec3(p), 1.0));
  const double x = voxel % uint32_t(n_[0]), y = voxel / uint32_t(n_[0]) % uint32_t(n_[1]);
  const double z = voxel / uint32_t(n_[0]) / uint32_t(n_[1]);
  return Vec3(local * glm::dvec3(n_[0] - 1, n_[1] - 1, n_[2] - 1) - glm::dvec3(x, y, z));
}

bool SdfGrid::intersect(const Ray& ray, uint32_t voxel, float tmax, float& t_hit) const {
  const glm::dvec3 scale(n_[0] - 1, n_[1] - 1, n_[2] - 1);
  const glm::dvec3 cell(voxel % uint32_t(n_[0]), voxel / uint32_t(n_[0]) % uint32_t(n_[1]),
                        voxel / uint32_t(n_[0]) / uint32_t(n_[1]));
  // The ray in the voxel's coordinates; the direction is not normalised, so t is the world's.
  const glm::dvec3 o = glm::dvec3(to_local_ * glm::dvec4(glm::dvec3(ray.origin), 1.0)) * scale - cell;
  const glm::dvec3 d = glm::dmat3(to_local_) * glm::dvec3(ray.dir) * scale;
  // Where it enters and leaves the voxel (and through which faces). The whole span is solved
  // whatever tmax is, so that a hit does not depend on the ray's length.
  double t0 = 0.0, t1 = kInfinity;
  int enter = -1, leave = -1;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (o[a] < 0.0 || o[a] > 1.0) return false;
      continue;
    }
    double ta = -o[a] / d[a], tb = (1.0 - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    if (ta > t0) t0 = ta, enter = a;
    if (tb < t1) t1 = tb, leave = a;
  }
  if (!(t0 < t1) || !(t0 < double(tmax))) return false;
  glm::dvec3 pb = glm::clamp(o + t0 * d, 0.0, 1.0), pe = glm::clamp(o + t1 * d, 0.0, 1.0);
  if (enter >= 0) pb[enter] = d[enter] > 0.0 ? 0.0 : 1.0;
  if (leave >= 0) pe[leave] = d[leave] > 0.0 ? 1.0 : 0.0;
  float c[8];
  corners(voxel, c);
  const Trilinear f(c);
  // f along the ray from the entry point: k0 + k1 s + k2 s^2 + k3 s^3.
  const double* a = f.a;
  const double X = pb.x, Y = pb.y, Z = pb.z, Dx = d.x, Dy = d.y, Dz = d.z;
  const double k0 = f(pb);
  const double k1 = a[1] * Dx + a[2] * Dy + a[3] * Dz + a[4] * (X * Dy + Y * Dx) + a[5] * (Y * Dz + Z * Dy) +
                    a[6] * (X * Dz + Z * Dx) + a[7] * (X * Y * Dz + X * Z * Dy + Y * Z * Dx);
  const double k2 = a[4] * Dx * Dy + a[5] * Dy * Dz + a[6] * Dx * Dz + a[7] * (X * Dy * Dz + Y * Dx * Dz + Z * Dx * Dy);
  const double k3 = a[7] * Dx * Dy * Dz;
  auto poly = [&](double s) { return ((k3 * s + k2) * s + k1) * s + k0; };
  auto slope = [&](double s) { return (3.0 * k3 * s + 2.0 * k2) * s + k1; };
  const double span = t1 - t0;
  // Monotonic pieces between the derivative's roots; the first with a change of sign holds
  // the first crossing.
  double s_at[4] = {0.0, 0.0, 0.0, span}, f_at[4] = {lerp3(c, pb), 0.0, 0.0, lerp3(c, pe)};
  int n = 1;
  double r[2];
  const int roots = quadratic_roots(3.0 * k3, 2.0 * k2, k1, r);
  for (int i = 0; i < roots; ++i) {
    if (r[i] > 0.0 && r[i] < span) s_at[n] = r[i], f_at[n] = poly(r[i]), ++n;
  }
  s_at[n] = span, f_at[n] = f_at[3];
  for (int i = 0; i < n; ++i) {
    double lo = s_at[i], hi = s_at[i + 1], f_lo = f_at[i];
    const double f_hi = f_at[i + 1];
    if (f_lo == 0.0 && lo == 0.0 && t0 == 0.0) continue;  // a ray leaving the surface it starts on
    if (f_lo * f_hi > 0.0) continue;
    double s;
    if (f_lo == 0.0) {
      s = lo;
    } else {
      // Newton's method kept inside the bracket (bisection when it would leave it).
      s = f_hi != f_lo ? lo + (hi - lo) * (f_lo / (f_lo - f_hi)) : 0.5 * (lo + hi);
      for (int it = 0; it < 64 && hi - lo > 1e-12 * std::max(1.0, span); ++it) {
        const double fs = poly(s);
        if (fs == 0.0) break;
        if ((fs < 0.0) == (f_lo < 0.0)) lo = s, f_lo = fs;
        else hi = s;
        const double g = slope(s);
        const double next = g != 0.0 ? s - fs / g : 0.5 * (lo + hi);
        s = next > lo && next < hi ? next : 0.5 * (lo + hi);
      }
    }
    const double t = t0 + s;
    if (!(t > 0.0) || !(t < double(tmax))) return false;
    t_hit = float(t);
    return t_hit > 0.0f && t_hit < tmax;
  }
  return false;
}

Vec3 SdfGrid::world_normal(const Vec3& local_gradient) const {
  const glm::dvec3 n = normal_matrix_ * glm::dvec3(local_gradient);
  const double len = glm::length(n);
  return len > 0.0 && std::isfinite(len) ? Vec3(n / len) : Vec3(0.0f, 0.0f, 1.0f);
}

Vec3 SdfGrid::voxel_gradient(const float c[8], const Vec3& q) const {
  const glm::dvec3 g = Trilinear(c).gradient(glm::clamp(glm::dvec3(q), 0.0, 1.0));
  return Vec3(g * glm::dvec3(n_[0] - 1, n_[1] - 1, n_[2] - 1));
}

Vec3 SdfGrid::normal(const Vec3& p, uint32_t voxel) const {
  float c[8];
  corners(voxel, c);
  return world_normal(voxel_gradient(c, to_voxel(p, voxel)));
}

Vec3 SdfGrid::point_gradient(int x, int y, int z) const {
  const int at[3] = {x, y, z};
  Vec3 g;
  for (int a = 0; a < 3; ++a) {
    int lo[3] = {x, y, z}, hi[3] = {x, y, z};
    lo[a] = std::max(at[a] - 1, 0);
    hi[a] = std::min(at[a] + 1, n_[a] - 1);
    g[a] = (value(hi[0], hi[1], hi[2]) - value(lo[0], lo[1], lo[2])) * float(n_[a] - 1) / float(hi[a] - lo[a]);
  }
  return g;
}

Vec3 SdfGrid::shading_normal(const Vec3& p, uint32_t voxel, const Vec3& geometric) const {
  if (normals_ == Normals::Analytic) return geometric;
  const Vec3 q = glm::clamp(to_voxel(p, voxel), 0.0f, 1.0f);
  const int x = int(voxel % uint32_t(n_[0])), y = int(voxel / uint32_t(n_[0]) % uint32_t(n_[1]));
  const int z = int(voxel / uint32_t(n_[0]) / uint32_t(n_[1]));
  Vec3 g(0.0f);
  for (int i = 0; i < 8; ++i) {
    const float w = ((i & 1) ? q.x : 1.0f - q.x) * ((i & 2) ? q.y : 1.0f - q.y) * ((i & 4) ? q.z : 1.0f - q.z);
    g += w * point_gradient(x + (i & 1), y + ((i >> 1) & 1), z + (i >> 2));
  }
  const Vec3 n = world_normal(g);
  // Smooth normals bend the geometric one, never turn it over.
  return glm::dot(n, geometric) > 0.0f ? n : geometric;
}

float SdfGrid::eval(const Vec3& p) const {
  const glm::dvec3 local(to_local_ * glm::dvec4(glm::dvec3(p), 1.0));
  const glm::dvec3 g = local * glm::dvec3(n_[0] - 1, n_[1] - 1, n_[2] - 1);
  int cell[3];
  for (int a = 0; a < 3; ++a) cell[a] = std::clamp(int(std::floor(g[a])), 0, n_[a] - 2);
  const uint32_t v = uint32_t((size_t(cell[2]) * size_t(n_[1]) + size_t(cell[1])) * size_t(n_[0]) + size_t(cell[0]));
  float c[8];
  corners(v, c);
  return float(lerp3(c, g - glm::dvec3(cell[0], cell[1], cell[2])));
}

}  // namespace caustica
