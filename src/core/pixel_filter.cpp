// Pixel filters sampled through a tabulated inverse CDF of their 1D profile's magnitude.
#include "core/pixel_filter.h"
#include <algorithm>
#include <cmath>

namespace caustica {
namespace {
constexpr int kTable = 1024;

double sinc(double x) {
  if (std::abs(x) < 1e-6) return 1.0;
  const double px = 3.14159265358979323846 * x;
  return std::sin(px) / px;
}
}  // namespace

PixelFilter PixelFilter::tabulated(const std::string& name, float radius, std::function<double(double)> profile) {
  PixelFilter f;
  f.name_ = name;
  f.radius_ = radius;
  f.profile_ = std::move(profile);
  // Midpoint rule per bin: the sampled filter is the profile's piecewise-constant version,
  // and the weights below make the estimate exactly that, normalised.
  std::vector<double> cdf(kTable + 1, 0.0);
  f.negative_.assign(kTable, 0);
  double signed_sum = 0.0;
  for (int i = 0; i < kTable; ++i) {
    const double x = -radius + 2.0 * radius * (i + 0.5) / kTable;
    const double v = f.profile_(x);
    signed_sum += v;
    f.negative_[size_t(i)] = v < 0.0;
    cdf[size_t(i) + 1] = cdf[size_t(i)] + std::abs(v);
  }
  f.cdf_.resize(cdf.size());
  for (size_t i = 0; i < cdf.size(); ++i) f.cdf_[i] = float(cdf[i] / cdf.back());
  f.norm_ = float(cdf.back() / signed_sum);
  return f;
}

PixelFilter PixelFilter::box() { return PixelFilter(); }

PixelFilter PixelFilter::gaussian(float stddev) {
  const double s2 = double(stddev) * stddev;
  return tabulated("gaussian", 4.0f * stddev, [s2](double x) { return std::exp(-0.5 * x * x / s2); });
}

PixelFilter PixelFilter::tent(float radius) {
  return tabulated("tent", radius, [radius](double x) { return std::max(0.0, 1.0 - std::abs(x) / radius); });
}

PixelFilter PixelFilter::mitchell(float b_in, float c_in, const std::string& name) {
  const double b = b_in, c = c_in;
  return tabulated(name, 2.0f, [b, c](double x) {
    x = std::abs(x);
    const double x2 = x * x, x3 = x2 * x;
    if (x < 1.0) return ((12 - 9 * b - 6 * c) * x3 + (-18 + 12 * b + 6 * c) * x2 + (6 - 2 * b)) / 6.0;
    if (x < 2.0) return ((-b - 6 * c) * x3 + (6 * b + 30 * c) * x2 + (-12 * b - 48 * c) * x + (8 * b + 24 * c)) / 6.0;
    return 0.0;
  });
}

PixelFilter PixelFilter::lanczos(int lobes) {
  const double l = lobes;
  return tabulated("lanczos", float(lobes), [l](double x) { return std::abs(x) < l ? sinc(x) * sinc(x / l) : 0.0; });
}

double PixelFilter::profile(double x) const {
  if (!profile_) return std::abs(x) <= 0.5 ? 1.0 : 0.0;
  return std::abs(x) <= radius_ ? profile_(x) : 0.0;
}

float PixelFilter::sample1(float u, float& sign) const {
  // The bin holding u, then linear within it (the CDF is piecewise linear).
  const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
  const size_t i = size_t(std::clamp<long>(long(it - cdf_.begin()) - 1, 0, kTable - 1));
  const float lo = cdf_[i], hi = cdf_[i + 1];
  const float t = hi > lo ? (u - lo) / (hi - lo) : 0.5f;
  sign = negative_[i] ? -1.0f : 1.0f;
  return -radius_ + 2.0f * radius_ * (float(i) + t) / float(kTable);
}

Vec2 PixelFilter::sample(const Vec2& u, float* weight) const {
  if (weight) *weight = 1.0f;
  if (is_box()) return u - Vec2(0.5f);
  float sx = 1.0f, sy = 1.0f;
  const Vec2 offset(sample1(u.x, sx), sample1(u.y, sy));
  if (weight) *weight = sx * sy * norm_ * norm_;
  return offset;
}

}  // namespace caustica
