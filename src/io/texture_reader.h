// Reads a texture block: {"type": "bitmap", "filename": ...} or {"type": "checkerboard", ...}.
#pragma once
#include <memory>
#include "io/bsdf_reader.h"

namespace caustica {

std::unique_ptr<Texture> read_texture(const MaterialContext& ctx, const nlohmann::json& t, const std::string& pointer);

}  // namespace caustica
