// Linear RGB float images and their files (EXR, HDR, PFM linear; PNG sRGB) via OpenImageIO.
#pragma once
#include <string>
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

// True for the file endings write_image understands.
bool is_supported_image_path(const std::string& path);
// Fails (InputError) when the extension is unknown or the folder does not exist or is not writable.
void check_output_path(const std::string& path);
// Writes through a temporary file in the same folder and renames it, so no half-written file
// ever carries the target name. `exposure` (stops) applies to PNG only.
void write_image(const std::string& path, const Image& image, float exposure = 0.0f);
Image read_image(const std::string& path);

float linear_to_srgb(float v);

}  // namespace caustica
