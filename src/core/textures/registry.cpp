// The texture family's table: one row a plugin.
#include "core/textures/registry.h"
#include "core/registry.h"
#include "core/textures/bitmap.h"
#include "core/textures/checkerboard.h"
#include "core/textures/mesh_attribute.h"

namespace caustica {

const std::vector<TexturePlugin>& texture_plugins() {
  static const std::vector<TexturePlugin> table = {
      {"bitmap", true, BitmapTexture::create, {"filename", "filter_type", "wrap_mode", "raw", "to_uv"}},
      {"checkerboard", true, CheckerboardTexture::create, {"color0", "color1", "to_uv"}},
      {"mesh_attribute", true, MeshAttributeTexture::create, {"name", "scale"}},
  };
  return table;
}

const TexturePlugin* find_texture_plugin(const std::string& name) { return find_plugin(texture_plugins(), name); }

std::string known_textures() { return plugin_names(texture_plugins()); }

}  // namespace caustica
