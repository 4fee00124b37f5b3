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

Distribution2D::Distribution2D(const float* weights, int nx, int ny) : nx_(nx), ny_(ny) {
  std::vector<float> row_sums(size_t(ny), 0.0f);
  rows_.reserve(size_t(ny));
  for (int y = 0; y < ny; ++y) {
    rows_.emplace_back(weights + size_t(y) * size_t(nx), size_t(nx));
    row_sums[size_t(y)] = rows_.back().total();
  }
  marginal_ = Distribution1D(row_sums.data(), row_sums.size());
}

Vec2 Distribution2D::sample(const Vec2& u, float* pdf) const {
  float v = u.y, w = u.x, pm = 0, pc = 0;
  const size_t row = marginal_.sample_remap(v, &pm);
  const size_t col = rows_[row].sample_remap(w, &pc);
  if (pdf) *pdf = pm * pc * float(nx_) * float(ny_);
  return Vec2((float(col) + w) / float(nx_), (float(row) + v) / float(ny_));
}

float Distribution2D::pdf(const Vec2& p) const {
  const int x = std::clamp(int(p.x * float(nx_)), 0, nx_ - 1);
  const int y = std::clamp(int(p.y * float(ny_)), 0, ny_ - 1);
  return marginal_.pmf(size_t(y)) * rows_[size_t(y)].pmf(size_t(x)) * float(nx_) * float(ny_);
}

}  // namespace caustica
