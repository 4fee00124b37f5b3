// Scene and integrator set-up from the command line.
#include "app/scene_setup.h"
#include <algorithm>
#include <iostream>
#include <tbb/info.h>

namespace caustica {

LoadedScene load_scene_with(const SceneOptions& options) {
  LoadedScene loaded = load_scene(options.scene, options.mitsuba);
  for (const std::string& w : loaded.warnings) std::cerr << "warning: " << w << "\n";
  RenderSettings& rs = loaded.scene->render;
  // A new size is a new film: a dimension not given keeps the film's (not a crop window's).
  if (options.width || options.height) {
    rs.width = options.width ? *options.width : loaded.scene->camera.film_width();
    rs.height = options.height ? *options.height : loaded.scene->camera.film_height();
  }
  if (options.spp) rs.spp = *options.spp;
  if (options.seed) rs.seed = *options.seed;
  if (options.max_depth) rs.max_depth = *options.max_depth;
  if (!options.accel.empty()) {
    AccelKind kind;
    if (!parse_accel(options.accel, kind)) throw InputError("--accel " + options.accel + ": expected bvh or embree");
    if (kind == AccelKind::Embree && !embree_available()) {
      throw InputError("--accel embree: this build of Caustica has no Embree (install libembree-dev and rebuild)");
    }
    loaded.scene->set_accel(kind);
  }
  // A new size is a new film: any crop window of the scene is dropped.
  if (options.width || options.height) loaded.scene->camera.set_resolution(rs.width, rs.height);
  return loaded;
}

std::unique_ptr<Integrator> integrator_for(const Scene& scene, const std::string& requested, const SceneOptions& options,
                                           bool lenient) {
  std::string type = scene.integrator_type;
  JsonSource settings = scene.integrator_settings;
  if (!requested.empty() && requested != type) {
    // The scene's settings were written for another integrator: use the defaults.
    if (!settings.value.empty() && !options.quiet) {
      std::cerr << "note: integrator " << requested << " replaces the scene's \"" << type << "\"; its settings in "
                << settings.pointer << " are not used\n";
    }
    type = requested;
    settings.value = nlohmann::json::object();
  }
  for (const auto& kv : options.integrator_overrides) {
    std::string flag = "--" + kv.first;
    std::replace(flag.begin(), flag.end(), '_', '-');
    const bool gather_only = kv.first == "gather_rays" || kv.first == "direct_samples" || kv.first == "irradiance_stride";
    if ((type != "photon" && type != "photon-direct") || (type == "photon-direct" && gather_only)) {
      if (lenient) continue;
      throw InputError(flag + " does not apply to integrator \"" + type + "\"");
    }
    settings.value[kv.first] = kv.second;
  }
  return create_integrator(type, settings, scene.render);
}

int thread_count(const SceneOptions& options) {
  return options.threads ? *options.threads : tbb::info::default_concurrency();
}

}  // namespace caustica
