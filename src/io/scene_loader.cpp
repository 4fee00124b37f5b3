// Scene file loader: every key validated, every error located by file and JSON pointer. This
// file: the document, the integrator block, materials and lights; the rest in loader.h's files.
#include "io/file_bytes.h"
#include "io/scene_loader.h"
#include <filesystem>
#include <map>
#include "core/bsdf/registry.h"
#include "core/lights/registry.h"
#include "core/media/registry.h"
#include "core/textures/mesh_attribute.h"
#include "core/textures/registry.h"
#include "io/bsdf_reader.h"
#include "io/json_params.h"
#include "io/loader.h"

namespace caustica::scene_loading {

void Loader::load(const json& doc) {
  r.check_object(doc, "", {"camera", "render", "integrator", "materials", "objects", "lights", "media"});
  if (doc.contains("render")) read_render(doc["render"], "/render");
  apply_overrides();
  if (doc.contains("media")) read_media(doc["media"], "/media");
  read_camera(r.require(doc, "", "camera"), "/camera");
  if (doc["camera"].contains("medium")) scene().camera_medium = medium_ref(doc["camera"], "/camera", "medium");
  if (doc.contains("integrator")) read_integrator(doc["integrator"], "/integrator");
  read_materials(r.require(doc, "", "materials"), "/materials");
  const json& objects = r.require(doc, "", "objects");
  if (!objects.is_array()) r.fail("/objects", "expected an array of objects");
  for (size_t i = 0; i < objects.size(); ++i) read_object(objects[i], child("/objects", i));
  if (doc.contains("lights")) {
    const json& lights = doc["lights"];
    if (!lights.is_array()) r.fail("/lights", "expected an array of lights");
    for (size_t i = 0; i < lights.size(); ++i) read_light(lights[i], child("/lights", i));
  }
  if (prims.empty()) r.fail("/objects", "the scene has no geometry");
  check_mesh_attribute_textures();
  if (scene().lights.empty()) {
    r.warn("", "the scene has no lights (no emissive material, no point light): the image will be black",
           out.warnings);
  }
  scene().build(std::move(prims));
}

void Loader::check_mesh_attribute_textures() {
  std::map<std::string, float> carried;  // each attribute's largest magnitude over the meshes
  for (const auto& m : scene().mesh_attributes) {
    for (const MeshAttribute& a : m->list) {
      float& most = carried[a.name];
      for (const Color& v : a.values) most = std::max(most, max_component(glm::abs(v)));
    }
  }
  for (const auto& t : scene().textures) {
    const auto* m = dynamic_cast<const MeshAttributeTexture*>(t.get());
    if (!m) continue;
    const std::string& place = texture_places_[t.get()];
    if (place.rfind("/lights", 0) == 0) {
      r.fail(place, "a mesh_attribute texture reads the values of the mesh a ray hits; a light's texture has no mesh "
                    "(an emitting mesh's radiance may be one)");
    }
    const auto it = carried.find(m->name());
    if (it != carried.end()) {
      if (double(it->second) * m->scale() > kMaxColor) {
        r.fail(child(place, "name"),
               "the attribute \"" + m->name() + "\" reaches " + format_number(double(it->second) * m->scale()) +
                   " (times scale), beyond the " + format_number(kMaxColor) + " a colour may hold");
      }
      continue;
    }
    std::string known;
    for (const auto& c : carried) known += (known.empty() ? "" : ", ") + c.first;
    r.fail(child(place, "name"),
           "no mesh in the scene carries the attribute \"" + m->name() + "\" (" +
               (known.empty() ? std::string("no mesh carries any: they come from PLY vertex or face properties")
                              : "the meshes carry: " + known) +
               ")");
  }
}

void Loader::read_integrator(const json& j, const std::string& p) {
  if (!j.is_object()) r.fail(p, "expected an object");
  JsonSource& src = out.integrator_settings;
  src.file = r.file();
  src.pointer = p;
  src.sources = r.sources();
  src.value = json::object();
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it.key() == "type") {
      out.integrator_type = r.string(it.value(), child(p, "type"));
    } else {
      src.value[it.key()] = it.value();
    }
  }
}

void Loader::read_materials(const json& j, const std::string& p) {
  if (!j.is_object()) r.fail(p, "expected an object mapping names to materials");
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string mp = child(p, it.key());
    const json& m = it.value();
    if (!m.is_object()) r.fail(mp, "expected an object");
    add_material(it.key(), m, mp);
  }
}

uint32_t Loader::add_material(const std::string& name, const json& m, const std::string& p) {
  std::vector<std::unique_ptr<Bsdf>> nested;
  const PluginContext ctx{r, base_dir, nested, scene().textures, out.warnings, &texture_places_};
  std::unique_ptr<Bsdf> mat = read_bsdf(ctx, m, p);
  for (auto& n : nested) {
    scene().materials.push_back(std::move(n));
    scene().material_names.push_back(name + " (nested)");
    emission_.push_back(Color(0.0f));
  }
  const uint32_t id = static_cast<uint32_t>(scene().materials.size());
  material_ids[name] = id;
  scene().materials.push_back(std::move(mat));
  scene().material_names.push_back(name);
  // A colour, or a texture over the object's UVs (kept alive by the scene).
  emission_.push_back(JsonParams(ctx, m, p).texture("emission", Color(0.0f)));
  return id;
}

uint32_t Loader::material_ref(const json& obj, const std::string& p, const char* key) {
  const std::string name = r.string(r.require(obj, p, key), child(p, key));
  auto it = material_ids.find(name);
  if (it == material_ids.end()) {
    std::string known;
    for (const auto& kv : material_ids) known += (known.empty() ? "" : ", ") + kv.first;
    r.fail(child(p, key), "unknown material \"" + name + "\" (known: " + known + ")");
  }
  return it->second;
}

void Loader::refuse_emission(const json& obj, const std::string& p, const std::string& shape) {
  if (!emission_[material_ref(obj, p)].is_black()) r.fail(child(p, "material"), shape + " cannot emit light here");
}

float Loader::sampling_weight(const json& j, const std::string& p) const {
  const double w = r.number_in(j["sampling_weight"], child(p, "sampling_weight"), 0.0, 1e9);
  if (!(w > 0.0)) r.fail(child(p, "sampling_weight"), "sampling_weight must be positive (a light never chosen adds nothing)");
  return float(w);
}

void Loader::read_light(const json& j, const std::string& p) {
  const LightPlugin& row = plugin_row(r, j, p, light_plugins(), "light", {"name", "sampling_weight"},
                                      "; area lights are objects with an emissive material");
  if (j.contains("name")) r.string(j["name"], child(p, "name"));
  // Lights read no nested BSDFs: `nested` stays empty (and may die with this call).
  std::vector<std::unique_ptr<Bsdf>> nested;
  const PluginContext ctx{r, base_dir, nested, scene().textures, out.warnings, &texture_places_};
  scene().lights.push_back(row.create(JsonParams(ctx, j, p)));
  if (j.contains("sampling_weight")) scene().lights.back()->set_sampling_weight(sampling_weight(j, p));
}

}  // namespace caustica::scene_loading

namespace caustica {
namespace fs = std::filesystem;
using nlohmann::json;
using scene_loading::Loader;

namespace {
template <class Plugin>
void list_family(std::vector<PluginListing>& out, const char* family, const std::vector<Plugin>& table, bool mitsuba) {
  for (const Plugin& p : table) {
    PluginListing l{family, p.name, mitsuba, {}};
    if constexpr (std::is_same_v<Plugin, BsdfPlugin> || is_family_row<Plugin>::value) {
      l.mitsuba = p.mitsuba;
    }
    l.keys.assign(p.keys.begin(), p.keys.end());
    out.push_back(std::move(l));
  }
}
}  // namespace

std::vector<PluginListing> scene_plugins() {
  std::vector<PluginListing> out;
  list_family(out, "bsdf", bsdf_plugins(), true);
  list_family(out, "texture", texture_plugins(), true);
  list_family(out, "light", light_plugins(), true);
  list_family(out, "medium", medium_plugins(), true);
  list_family(out, "phase", phase_plugins(), true);
  list_family(out, "volume", volume_plugins(), true);
  // Our shapes are not Mitsuba's: its shapes are translated into these.
  list_family(out, "shape", scene_loading::shape_plugins(), false);
  return out;
}


namespace {
// Scene files are UTF-8 (with or without a byte-order mark). UTF-16 and UTF-32 ones, as some
// Windows editors save them, would otherwise be reported as a JSON syntax error.
void check_encoding(const std::string& text, const std::string& file) {
  auto starts = [&](const char* bom, size_t n) { return text.size() >= n && text.compare(0, n, bom, n) == 0; };
  // Without a byte-order mark: "<" or "{" as UTF-16 or UTF-32 has a NUL beside it, which
  // a file of zeros (not text at all, left to the syntax error) does not.
  const bool nul_beside_text = (text.size() >= 2 && (text[0] == '\0') != (text[1] == '\0')) ||
                               (text.size() >= 4 && text.compare(0, 3, "\0\0\0", 3) == 0 && text[3] != '\0');
  const bool wide = starts("\xFF\xFE", 2) || starts("\xFE\xFF", 2) || starts("\x00\x00\xFE\xFF", 4) || nul_beside_text;
  if (wide) {
    throw InputError(file + ": the file is encoded as UTF-16 or UTF-32; scene files must be UTF-8 "
                            "(convert it, e.g. iconv -f UTF-16 -t UTF-8)");
  }
}
}  // namespace

LoadedScene parse_scene(const std::string& text, const std::string& file, const std::string& base_dir,
                        const MitsubaOptions& mitsuba, const RenderOverrides& overrides) {
  json doc;
  std::shared_ptr<const SourceMap> sources;
  std::vector<std::string> warnings;
  check_encoding(text, file);
  if (looks_like_xml(text)) {
    TranslatedScene t = read_mitsuba(text, file, base_dir, mitsuba);
    doc = std::move(t.doc);
    sources = std::move(t.sources);
    warnings = std::move(t.warnings);
  } else {
    if (!mitsuba.xml.defines.empty()) {
      throw InputError(file + ": -D " + mitsuba.xml.defines.begin()->first +
                       "=... sets a parameter of a Mitsuba XML scene; this is a JSON scene, which has none");
    }
    doc = parse_json_text(text, file);
  }
  Loader loader{JsonReader(file, sources), base_dir, overrides, {}, {}, {}};
  loader.out.scene = std::make_unique<Scene>();
  loader.out.scene->source_file = file;
  loader.out.warnings = std::move(warnings);
  loader.load(doc);
  if (loader.degenerate_ > 3) {
    loader.out.warnings.push_back(file + ": " + std::to_string(loader.degenerate_) +
                                  " degenerate triangles left out in all");
  }
  return std::move(loader.out);
}

LoadedScene load_scene(const std::string& path, const MitsubaOptions& mitsuba, const RenderOverrides& overrides) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path + ": scene file not found");
  if (fs::is_directory(path, ec)) throw InputError(path + ": is a directory, not a scene file");
  // A FIFO or device would block or never end: only regular files are read.
  if (!fs::is_regular_file(path, ec)) throw InputError(path + ": not a regular file");
  const std::string text = read_file_bytes(path, "scene file");
  const std::string base = fs::path(path).parent_path().string();
  return parse_scene(text, path, base.empty() ? "." : base, mitsuba, overrides);
}

}  // namespace caustica
