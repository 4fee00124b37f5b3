// Warping of uniform samples to directions and points, with the matching densities.
#pragma once
#include "core/math.h"
#include <vector>

namespace caustica {

Vec3 sample_cosine_hemisphere(const Vec2& u);  // local frame, z up
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0 ? cos_theta * kInvPi : 0; }

Vec3 sample_uniform_sphere(const Vec2& u);
inline float uniform_sphere_pdf() { return 1.0f / (4.0f * kPi); }

Vec3 sample_uniform_hemisphere(const Vec2& u);  // local frame, z up
inline float uniform_hemisphere_pdf() { return 1.0f / (2.0f * kPi); }

Vec2 sample_concentric_disk(const Vec2& u);  // unit disc
inline float unit_disk_pdf() { return kInvPi; }

// Barycentric (b0, b1) uniformly distributed over a triangle; b2 = 1 - b0 - b1.
Vec2 sample_uniform_triangle(const Vec2& u);

// Direction uniform within a cone around +z with cos(half angle) = cos_max.
Vec3 sample_uniform_cone(const Vec2& u, float cos_max);
inline float uniform_cone_pdf(float cos_max) { return 1.0f / (2.0f * kPi * (1.0f - cos_max)); }

// Discrete distribution over weights (for choosing lights by power, triangles by area).
class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(const float* weights, size_t n);
  size_t size() const { return pdf_.size(); }
  float total() const { return total_; }
  size_t sample(float u, float* pmf = nullptr) const;
  // Samples an index and rescales u to a fresh uniform number within that bucket.
  size_t sample_remap(float& u, float* pmf = nullptr) const;
  float pmf(size_t i) const { return pdf_[i]; }

 private:
  std::vector<float> cdf_, pdf_;
  float total_ = 0;
};

// Piecewise-constant density over the unit square from an nx x ny grid of weights (row-major,
// ny rows), sampled by the marginal over rows then the row's conditional.
class Distribution2D {
 public:
  Distribution2D() = default;
  Distribution2D(const float* weights, int nx, int ny);
  // A point in [0, 1)^2 and its density with respect to area in the unit square.
  Vec2 sample(const Vec2& u, float* pdf) const;
  float pdf(const Vec2& p) const;

 private:
  std::vector<Distribution1D> rows_;
  Distribution1D marginal_;
  int nx_ = 0, ny_ = 0;
};

}  // namespace caustica
