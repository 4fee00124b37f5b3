// Pixel filters sampled through a tabulated inverse CDF of their 1D profile.
#include "core/pixel_filter.h"
#include <algorithm>
#include <cmath>

namespace caustica {
namespace {
constexpr int kTable = 1024;

template <class F>
std::vector<float> tabulate(float radius, F profile) {
  std::vector<double> cdf(kTable + 1, 0.0);
  for (int i = 0; i < kTable; ++i) {
    // Midpoint rule per bin.
    const double x = -radius + 2.0 * radius * (i + 0.5) / kTable;
    cdf[size_t(i) + 1] = cdf[size_t(i)] + std::max(0.0, profile(x));
  }
  std::vector<float> out(cdf.size());
  for (size_t i = 0; i < cdf.size(); ++i) out[i] = float(cdf[i] / cdf.back());
  return out;
}
}  // namespace

PixelFilter PixelFilter::box() { return PixelFilter(); }

PixelFilter PixelFilter::gaussian(float stddev) {
  PixelFilter f;
  f.name_ = "gaussian";
  f.radius_ = 4.0f * stddev;
  const double s2 = double(stddev) * stddev;
  f.cdf_ = tabulate(f.radius_, [&](double x) { return std::exp(-0.5 * x * x / s2); });
  return f;
}

PixelFilter PixelFilter::tent(float radius) {
  PixelFilter f;
  f.name_ = "tent";
  f.radius_ = radius;
  f.cdf_ = tabulate(radius, [&](double x) { return 1.0 - std::abs(x) / radius; });
  return f;
}

float PixelFilter::sample1(float u) const {
  // The bin holding u, then linear within it (the CDF is piecewise linear).
  const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
  const size_t i = size_t(std::clamp<long>(long(it - cdf_.begin()) - 1, 0, kTable - 1));
  const float lo = cdf_[i], hi = cdf_[i + 1];
  const float t = hi > lo ? (u - lo) / (hi - lo) : 0.5f;
  return -radius_ + 2.0f * radius_ * (float(i) + t) / float(kTable);
}

Vec2 PixelFilter::sample(const Vec2& u) const {
  if (is_box()) return u - Vec2(0.5f);
  return Vec2(sample1(u.x), sample1(u.y));
}

}  // namespace caustica
