// Linear RGB float images in memory.
#include "core/image.h"
#include <cmath>

namespace caustica {

Color Image::mean() const {
  glm::dvec3 sum(0.0);
  for (const Color& c : pixels) sum += glm::dvec3(c);
  return pixels.empty() ? Color(0.0f) : Color(sum / double(pixels.size()));
}

float linear_to_srgb(float v) {
  if (!(v > 0.0f)) return 0.0f;
  if (v >= 1.0f) return 1.0f;
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

}  // namespace caustica
