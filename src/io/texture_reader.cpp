// Texture blocks: the registry's row checks the keys, the plugin's create() reads the values.
#include "io/texture_reader.h"
#include "core/textures/registry.h"

namespace caustica {

std::unique_ptr<Texture> read_texture(const PluginContext& ctx, const nlohmann::json& t, const std::string& p) {
  return plugin_row(ctx.r, t, p, texture_plugins(), "texture").create(JsonParams(ctx, t, p));
}

}  // namespace caustica
