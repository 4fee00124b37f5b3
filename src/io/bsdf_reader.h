// Reads one material block of a JSON scene, with Mitsuba 3's plugin and parameter names.
#pragma once
#include <memory>
#include <vector>
#include <nlohmann/json.hpp>
#include "io/json_reader.h"
#include "core/material.h"
#include "core/textures/texture.h"

namespace caustica {

// What reading a material needs besides its block: materials nested inside another
// (twosided's `bsdf`) and textures go to `nested` and `textures`, which the scene keeps alive;
// texture files are found relative to `base_dir`; warnings (e.g. energy-creating albedos) go
// to `warnings`.
struct MaterialContext {
  const JsonReader& r;
  std::string base_dir;
  std::vector<std::unique_ptr<Material>>& nested;
  std::vector<std::unique_ptr<Texture>>& textures;
  std::vector<std::string>& warnings;
};

std::unique_ptr<Material> read_material(const MaterialContext& ctx, const nlohmann::json& m, const std::string& pointer);

// The material type names read_material knows, for messages.
const char* known_material_types();

}  // namespace caustica
