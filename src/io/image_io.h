// Image files (EXR, HDR, PFM linear; PNG sRGB) via OpenImageIO.
#pragma once
#include <string>
#include "core/image.h"
#include "io/atomic_file.h"

namespace caustica {

// True for the file endings write_image understands.
bool is_supported_image_path(const std::string& path);
// Fails (InputError) when the extension is unknown or check_output_file fails.
void check_output_path(const std::string& path);
// Writes all or nothing (io/atomic_file.h): no half-written file ever carries the target name.
// `exposure` (stops) applies to PNG only.
void write_image(const std::string& path, const Image& image, float exposure = 0.0f);
// Writes the image into `file`'s temporary (the format by the target's extension), to be
// committed with others: a render's image and its AOVs appear together or not at all.
void write_image_to(AtomicFile& file, const Image& image, float exposure = 0.0f);
Image read_image(const std::string& path);

}  // namespace caustica
