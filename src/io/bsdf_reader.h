// Reads one BSDF block of a JSON scene through the BSDF registry (core/bsdf/registry.h): the
// block's keys are checked against the plugin's row, then the plugin reads its own values.
#pragma once
#include <memory>
#include <vector>
#include <nlohmann/json.hpp>
#include "core/bsdf/bsdf.h"
#include "core/textures/texture.h"
#include "io/json_reader.h"

namespace caustica {

// What reading a BSDF needs besides its block: BSDFs nested inside another (twosided's `bsdf`)
// and textures go to `nested` and `textures`, which the scene keeps alive; texture files are
// found relative to `base_dir`; warnings (e.g. energy-creating albedos) go to `warnings`.
struct MaterialContext {
  const JsonReader& r;
  std::string base_dir;
  std::vector<std::unique_ptr<Bsdf>>& nested;
  std::vector<std::unique_ptr<Texture>>& textures;
  std::vector<std::string>& warnings;
};

// A scene's material block: a BSDF plus, where its plugin allows, the "emission" of the area
// light that objects of this material become (read by the scene loader, not here).
std::unique_ptr<Bsdf> read_bsdf(const MaterialContext& ctx, const nlohmann::json& m, const std::string& pointer);

}  // namespace caustica
