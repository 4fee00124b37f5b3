// Scene and integrator set-up from the command line.
#include "app/scene_setup.h"
#include <algorithm>
#include <fstream>
#include <sstream>
#include <iostream>
#include <tbb/info.h>
#include <thread>
#include "trace/cluster.h"

namespace caustica {

LoadedScene load_scene_with(const SceneOptions& options) {
  RenderOverrides overrides;
  overrides.width = options.width;
  overrides.height = options.height;
  overrides.spp = options.spp;
  overrides.seed = options.seed;
  overrides.max_depth = options.max_depth;
  if (!options.accel.empty()) {
    AccelKind kind;
    if (!parse_accel(options.accel, kind)) throw InputError("--accel " + options.accel + ": expected bvh or embree");
    if (choose_accel(kind) != kind) {
      throw InputError("--accel embree: this build of Caustica has no Embree (install libembree-dev and rebuild)");
    }
    overrides.accel = kind;
  }
  if (!options.light_sampler.empty()) {
    LightSamplerKind kind;
    if (!parse_light_sampler(options.light_sampler, kind)) {
      throw InputError("--light-sampler " + options.light_sampler + ": expected tree or power");
    }
    overrides.light_sampler = kind;
  }
  LoadedScene loaded = load_scene(options.scene, options.mitsuba, overrides);
  for (const std::string& w : loaded.warnings) std::cerr << "warning: " << w << "\n";
  return loaded;
}

std::unique_ptr<Integrator> integrator_for(const LoadedScene& loaded, const std::string& spec, const SceneOptions& options,
                                           bool lenient) {
  // "type:key=value:key=value": settings given with the name (converge compares variants).
  std::string requested = spec;
  std::vector<std::pair<std::string, nlohmann::json>> spec_settings;
  if (const size_t colon = spec.find(':'); colon != std::string::npos) {
    requested = spec.substr(0, colon);
    size_t at = colon + 1;
    while (at <= spec.size()) {
      const size_t end = std::min(spec.find(':', at), spec.size());
      const std::string item = spec.substr(at, end - at);
      const size_t eq = item.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == item.size()) {
        throw InputError("integrator \"" + spec + "\": expected TYPE:KEY=VALUE, not \"" + item + "\"");
      }
      nlohmann::json value = nlohmann::json::parse(item.substr(eq + 1), nullptr, false);
      if (value.is_discarded()) value = item.substr(eq + 1);  // a bare word is a string
      for (const auto& kv : spec_settings) {
        if (kv.first == item.substr(0, eq)) throw InputError("integrator \"" + spec + "\": " + kv.first + " given twice");
      }
      spec_settings.emplace_back(item.substr(0, eq), value);
      at = end + 1;
    }
  }
  const Scene& scene = *loaded.scene;
  std::string type = loaded.integrator_type;
  JsonSource settings = loaded.integrator_settings;
  if (!requested.empty() && !find_integrator_plugin(requested)) {
    throw InputError(unknown_integrator(requested));
  }
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
    const std::string flag = integrator_flag(kv.first);
    // A flag applies to the integrators whose registry row lists its key.
    const IntegratorPlugin* row = find_integrator_plugin(type);
    const bool applies = row && row->reads(kv.first);
    if (!applies) {
      if (lenient) continue;
      throw InputError(flag + " does not apply to integrator \"" + type + "\"");
    }
    // Checked on its own first, so that a value the integrator refuses is blamed on its flag,
    // not on the scene file the merged settings are read as.
    JsonSource alone;
    alone.value = nlohmann::json::object({{kv.first, kv.second}});
    alone.file = flag + " " + kv.second.dump();
    try {
      create_integrator(type, alone, scene.render);
    } catch (const InputError& e) {
      std::string message = e.what();
      const std::string prefix = alone.file + ": /" + kv.first + ": ";
      if (message.rfind(prefix, 0) == 0) message = alone.file + ": " + message.substr(prefix.size());
      throw InputError(message);
    }
    settings.value[kv.first] = kv.second;
  }
  for (const auto& kv : spec_settings) {
    for (const auto& flag : options.integrator_overrides) {
      if (flag.first == kv.first) {
        std::string name = integrator_flag(kv.first);
        const IntegratorSetting* setting = find_integrator_setting(kv.first);
        if (setting && setting->kind == SettingKind::Boolean) name += "/--no-" + name.substr(2);
        throw InputError("integrator \"" + spec + "\" sets " + kv.first + " and so does " + name + ": give it once");
      }
    }
    settings.value[kv.first] = kv.second;
  }
  if (settings.file.empty()) settings.file = options.scene;
  if (settings.pointer.empty()) settings.pointer = "/integrator";
  std::unique_ptr<Integrator> integrator;
  if (spec_settings.empty()) {
    integrator = create_integrator(type, settings, scene.render);
  } else {
    // A setting given with the name that the integrator refuses: say where it came from.
    try {
      integrator = create_integrator(type, settings, scene.render);
    } catch (const InputError& e) {
      throw InputError("integrator \"" + spec + "\": " + e.what());
    }
  }
  return integrator;
}

int thread_count(const SceneOptions& options) {
  if (options.threads) return *options.threads;
  // The ranks on this machine share its cores, and no rank takes more than the cores it may run
  // on (mpirun binds ranks to a core or a socket).
  // hardware_concurrency() is 0 where it cannot tell: then the usable cores are the share.
  const int usable = tbb::info::default_concurrency();
  const int cores = int(std::thread::hardware_concurrency());
  const int share = cores > 0 ? cores / Cluster::world().local_size() : usable;
  return std::max(1, std::min(usable, share));
}

void check_ranks_agree(const SceneOptions& options, const std::string& command_settings,
                       const std::vector<const Integrator*>& integrators) {
  const Cluster& cluster = Cluster::world();
  if (!cluster.distributed()) return;
  for (const Integrator* integrator : integrators) {
    if (!integrator->passes_independent()) {
      throw InputError("integrator \"" + integrator->name() +
                       "\" renders its passes in order (each pass's radii follow from the last): run it on one rank");
    }
  }
  // Everything that shapes the image; not --threads, -q or the output's name.
  std::ostringstream s;
  std::ifstream file(options.scene, std::ios::binary);
  s << options.scene << "\n" << file.rdbuf() << "\n";
  auto put = [&](const char* name, const auto& v) {
    s << name << "=";
    if (v) s << *v;
    s << "\n";
  };
  put("spp", options.spp);
  put("width", options.width);
  put("height", options.height);
  put("max_depth", options.max_depth);
  put("seed", options.seed);
  for (const auto& [key, value] : options.integrator_overrides) s << key << "=" << value.dump() << "\n";
  for (const auto& [name, value] : options.mitsuba.xml.defines) s << "-D" << name << "=" << value << "\n";
  s << options.mitsuba.ignore_unsupported << options.accel << options.light_sampler << "\n" << command_settings;
  if (!cluster.same_everywhere(std::hash<std::string>{}(s.str()))) {
    throw InputError("the ranks were started with different scene files or settings: every rank must render the "
                     "same image (same scene file, options, integrator, --spp, --seed, --time)");
  }
}

}  // namespace caustica
