// Warping functions (pbrt-v4 chapter A.5 and Shirley-Chiu concentric mapping).
#include "core/sampling.h"

namespace caustica {

Vec2 sample_concentric_disk(const Vec2& u) {
  const Vec2 o = 2.0f * u - Vec2(1.0f);
  if (o.x == 0.0f && o.y == 0.0f) return Vec2(0.0f);
  float r, theta;
  if (std::abs(o.x) > std::abs(o.y)) {
    r = o.x;
    theta = (kPi / 4.0f) * (o.y / o.x);
  } else {
    r = o.y;
    theta = (kPi / 2.0f) - (kPi / 4.0f) * (o.x / o.y);
  }
  return r * Vec2(std::cos(theta), std::sin(theta));
}

Vec3 sample_cosine_hemisphere(const Vec2& u) {
  const Vec2 d = sample_concentric_disk(u);
  const float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return Vec3(d.x, d.y, z);
}

Vec3 sample_uniform_sphere(const Vec2& u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

Vec3 sample_uniform_hemisphere(const Vec2& u) {
  const float z = u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

Vec2 sample_uniform_triangle(const Vec2& u) {
  // Heitz 2019, "A low-distortion map between triangle and square".
  float b0, b1;
  if (u.x < u.y) {
    b0 = u.x / 2.0f;
    b1 = u.y - b0;
  } else {
    b1 = u.y / 2.0f;
    b0 = u.x - b1;
  }
  return Vec2(b0, b1);
}

Vec3 sample_uniform_cone(const Vec2& u, float cos_max) {
  const float z = 1.0f - u.x * (1.0f - cos_max);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

Distribution1D::Distribution1D(const float* weights, size_t n) : cdf_(n + 1), pdf_(n) {
  double sum = 0;
  cdf_[0] = 0;
  for (size_t i = 0; i < n; ++i) {
    sum += std::max(0.0f, weights[i]);
    cdf_[i + 1] = static_cast<float>(sum);
  }
  total_ = static_cast<float>(sum);
  for (size_t i = 0; i < n; ++i) {
    pdf_[i] = sum > 0 ? static_cast<float>(std::max(0.0f, weights[i]) / sum) : 1.0f / n;
    cdf_[i + 1] = sum > 0 ? static_cast<float>(cdf_[i + 1] / sum) : float(i + 1) / n;
  }
  cdf_[n] = 1.0f;
}

size_t Distribution1D::sample(float u, float* pmf) const {
  float v = u;
  return sample_remap(v, pmf);
}

size_t Distribution1D::sample_remap(float& u, float* pmf) const {
  // Last index i with cdf[i] <= u, skipping zero-weight entries.
  auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
  size_t i = static_cast<size_t>(std::max<std::ptrdiff_t>(0, (it - cdf_.begin()) - 1));
  i = std::min(i, pdf_.size() - 1);
  while (pdf_[i] == 0.0f && i > 0) --i;
  while (pdf_[i] == 0.0f && i + 1 < pdf_.size()) ++i;
  if (pmf) *pmf = pdf_[i];
  const float width = cdf_[i + 1] - cdf_[i];
  u = width > 0 ? std::min((u - cdf_[i]) / width, 0x1.fffffep-1f) : 0.5f;
  return i;
}

}  // namespace caustica
