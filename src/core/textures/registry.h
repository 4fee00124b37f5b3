// The texture family's one table: name, whether Mitsuba knows it by that name, create, keys.
#pragma once
#include <memory>
#include <string>
#include <vector>
#include "core/params.h"
#include "core/registry.h"
#include "core/textures/texture.h"

namespace caustica {

using TexturePlugin = FamilyRow<Texture>;

const std::vector<TexturePlugin>& texture_plugins();
const TexturePlugin* find_texture_plugin(const std::string& name);
std::string known_textures();

}  // namespace caustica
