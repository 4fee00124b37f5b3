// Image files (EXR, HDR, PFM linear; PNG sRGB) via OpenImageIO.
#pragma once
#include <string>
#include "core/image.h"

namespace caustica {

// True for the file endings write_image understands.
bool is_supported_image_path(const std::string& path);
// Fails (InputError) when the extension is unknown or the folder does not exist or is not writable.
void check_output_path(const std::string& path);
// Writes through a temporary file in the same folder and renames it, so no half-written file
// ever carries the target name. `exposure` (stops) applies to PNG only.
void write_image(const std::string& path, const Image& image, float exposure = 0.0f);
Image read_image(const std::string& path);

}  // namespace caustica
