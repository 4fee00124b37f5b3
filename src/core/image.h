// Linear RGB float images in memory (their files: io/image_io.h).
#pragma once
#include <cmath>
#include <vector>
#include "core/math.h"

namespace caustica {

struct Image {
  int width = 0, height = 0;
  std::vector<Color> pixels;
  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h), Color(0.0f)) {}
  Color& at(int x, int y) { return pixels[size_t(y) * width + x]; }
  const Color& at(int x, int y) const { return pixels[size_t(y) * width + x]; }
  Color mean() const;
};

// The sRGB transfer curve, clamped to [0, 1].
float linear_to_srgb(float v);
// Its inverse: an sRGB-encoded value in [0, 1] to linear.
inline float srgb_to_linear(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }

}  // namespace caustica
