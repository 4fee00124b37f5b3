// Reads JSON scene files (format: docs/scene-format.md).
#pragma once
#include <optional>
#include <string>
#include <vector>
#include "io/mitsuba/translate.h"
#include "core/scene.h"

namespace caustica {

// What the command line sets over the scene file's render block. Applied while the scene is
// read, before it is built: the accelerator is built once, for the backend that renders. A
// width or height is a new film: a dimension not given keeps the film's, and the scene's crop
// window is dropped.
struct RenderOverrides {
  std::optional<int> width, height, spp, max_depth;
  std::optional<uint64_t> seed;
  std::optional<AccelKind> accel;  // checked by the command line (Embree must be available)
  std::optional<LightSamplerKind> light_sampler;
};

struct LoadedScene {
  std::unique_ptr<Scene> scene;
  std::vector<std::string> warnings;
  std::string integrator_type = "path";
  JsonSource integrator_settings;  // the integrator block without "type" (the integrator reads it)
  size_t triangle_count = 0, sphere_count = 0;
};

// Every plugin a scene file can name, family by family (bsdf, texture, light, shape), with
// whether Mitsuba knows it by that name and the keys its block takes besides "type": for
// `caustica plugins` and the fuzz dictionaries, taken from the registries.
struct PluginListing {
  std::string family, name;
  bool mitsuba = false;
  std::vector<std::string> keys;
};
std::vector<PluginListing> scene_plugins();

// Throws InputError naming the file and the place in it. A file whose text starts with '<' is a
// Mitsuba XML scene (read by its root element, not its extension); anything else is our JSON.
LoadedScene load_scene(const std::string& path, const MitsubaOptions& mitsuba = {}, const RenderOverrides& overrides = {});
// Parses scene text; `file` names it in messages, `base_dir` resolves mesh paths.
LoadedScene parse_scene(const std::string& text, const std::string& file, const std::string& base_dir,
                        const MitsubaOptions& mitsuba = {}, const RenderOverrides& overrides = {});

}  // namespace caustica
