// BSDF blocks: the registry's row checks the keys, the plugin's create() reads the values.
#include "io/bsdf_reader.h"
#include "core/bsdf/registry.h"

namespace caustica {

std::unique_ptr<Bsdf> read_bsdf(const PluginContext& ctx, const nlohmann::json& m, const std::string& p, bool nested) {
  const JsonReader& r = ctx.r;
  const BsdfPlugin* named = m.is_object() && m.contains("type") && m["type"].is_string()
                                ? find_bsdf_plugin(m["type"].get<std::string>())
                                : nullptr;
  if (named && m.contains("emission")) {
    if (nested) r.fail(child(p, "emission"), "emission belongs on the outermost material, not inside it");
    if (!named->can_emit) r.fail(child(p, "emission"), "a " + std::string(named->name) + " material cannot emit light");
  }
  const bool may_emit = named && named->can_emit && !nested;
  const BsdfPlugin& row = plugin_row(r, m, p, bsdf_plugins(), "material",
                                     may_emit ? std::vector<const char*>{"emission"} : std::vector<const char*>{});
  return row.create(JsonParams(ctx, m, p));
}

}  // namespace caustica
