// Participating media in a JSON scene: the "media" block (names to medium blocks, through the
// medium family's table), objects' "interior" and "exterior", the camera's "medium".
#include "core/media/registry.h"
#include "io/json_params.h"
#include "io/loader.h"

namespace caustica::scene_loading {

void Loader::read_media(const json& j, const std::string& p) {
  if (!j.is_object()) r.fail(p, "expected an object mapping names to media");
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string mp = child(p, it.key());
    const MediumPlugin& row = plugin_row(r, it.value(), mp, medium_plugins(), "medium");
    std::vector<std::unique_ptr<Bsdf>> nested;  // (media nest no BSDFs)
    const PluginContext ctx{r, base_dir, nested, scene().textures, out.warnings, &texture_places_};
    medium_ids_[it.key()] = int32_t(scene().media.size());
    scene().media.push_back(row.create(JsonParams(ctx, it.value(), mp)));
  }
}

int32_t Loader::medium_ref(const json& obj, const std::string& p, const char* key) {
  const std::string name = r.string(obj[key], child(p, key));
  const auto it = medium_ids_.find(name);
  if (it != medium_ids_.end()) return it->second;
  std::string known;
  for (const auto& kv : medium_ids_) known += (known.empty() ? "" : ", ") + kv.first;
  r.fail(child(p, key), "unknown medium \"" + name + "\" (" +
                            (known.empty() ? std::string("the scene's \"media\" block defines none") : "known: " + known) +
                            ")");
}

uint16_t Loader::media_interface(const json& obj, const std::string& p) {
  const int32_t interior = obj.contains("interior") ? medium_ref(obj, p, "interior") : -1;
  const int32_t exterior = obj.contains("exterior") ? medium_ref(obj, p, "exterior") : -1;
  if (interior < 0 && exterior < 0) return 0;
  const auto key = std::make_pair(interior, exterior);
  const auto it = interface_ids_.find(key);
  if (it != interface_ids_.end()) return it->second;
  if (scene().interfaces.size() >= 65535) r.fail(p, "more than 65535 different pairs of interior and exterior media");
  scene().interfaces.push_back(MediumInterface{interior, exterior});
  const uint16_t id = uint16_t(scene().interfaces.size());
  interface_ids_[key] = id;
  return id;
}

}  // namespace caustica::scene_loading
