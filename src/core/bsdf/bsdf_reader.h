// Reads one material block of a JSON scene, with Mitsuba 3's plugin and parameter names.
#pragma once
#include <memory>
#include <vector>
#include <nlohmann/json.hpp>
#include "core/json_reader.h"
#include "core/material.h"

namespace caustica {

// Materials nested inside another (twosided's `bsdf`) are appended to `nested`, which the
// scene keeps alive. Warnings (e.g. energy-creating albedos) go to `warnings`.
std::unique_ptr<Material> read_material(const JsonReader& r, const nlohmann::json& m, const std::string& pointer,
                                        std::vector<std::unique_ptr<Material>>& nested,
                                        std::vector<std::string>& warnings);

// The material type names read_material knows, for messages.
const char* known_material_types();

}  // namespace caustica
