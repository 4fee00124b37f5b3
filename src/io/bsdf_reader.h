// Reads one BSDF block of a JSON scene through the BSDF registry (core/bsdf/registry.h): the
// block's keys are checked against the plugin's row, then the plugin reads its own values.
#pragma once
#include <memory>
#include <nlohmann/json.hpp>
#include "core/bsdf/bsdf.h"
#include "io/json_params.h"

namespace caustica {

// A scene's material block: a BSDF plus, where its plugin allows and it is not `nested` in
// another, the "emission" of the area light that objects of this material become (read by the
// scene loader, not here).
std::unique_ptr<Bsdf> read_bsdf(const PluginContext& ctx, const nlohmann::json& m, const std::string& pointer,
                                bool nested = false);

}  // namespace caustica
