// Reads a texture block through the texture registry (core/textures/registry.h).
#pragma once
#include <memory>
#include <nlohmann/json.hpp>
#include "io/json_params.h"

namespace caustica {

std::unique_ptr<Texture> read_texture(const PluginContext& ctx, const nlohmann::json& t, const std::string& pointer);

}  // namespace caustica
