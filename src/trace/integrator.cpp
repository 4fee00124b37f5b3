// The integrator family's tables: every integrator by name with its keys (Tungsten's
// IntegratorFactory in spirit), and every settings key with its kind and help.
#include "trace/integrator.h"
#include <algorithm>
#include <iostream>
#include "core/registry.h"
#include "io/json_params.h"
#include "trace/path.h"
#include "trace/photon_integrator.h"
#include "trace/sppm.h"
#include "trace/whitted.h"

namespace caustica {

const std::vector<IntegratorPlugin>& integrator_plugins() {
  static const std::vector<IntegratorPlugin> table = {
      {"path", PathIntegrator::create, {"rr_depth", "hide_emitters"}},
      {"photon", PhotonIntegrator::create,
       {"photons", "caustic_photons", "global_k", "caustic_k", "global_radius", "caustic_radius", "gather_rays",
        "direct_samples", "glossy_direct_samples", "irradiance_stride", "glossy_threshold", "caustic_threshold", "hide_emitters", "progressive",
        "alpha", "path_fallback", "final_gather", "volume_k", "volume_radius", "volume_boundary"}},
      {"photon-direct", PhotonIntegrator::create_direct,
       {"photons", "caustic_photons", "global_k", "caustic_k", "global_radius", "caustic_radius", "glossy_threshold",
        "hide_emitters", "progressive", "alpha", "volume_k", "volume_radius", "volume_boundary"}},
      {"sppm", SppmIntegrator::create, {"photons", "radius", "alpha", "glossy_threshold", "hide_emitters"}},
      {"whitted", WhittedIntegrator::create, {}},
  };
  return table;
}

const std::vector<IntegratorSetting>& integrator_settings() {
  static const std::vector<IntegratorSetting> table = {
      {"photons", SettingKind::Integer, "Photons stored in the global map (sppm: per pass)"},
      {"caustic_photons", SettingKind::Integer, "Photons stored in the caustic map"},
      {"global_k", SettingKind::Integer, "Nearest photons per global-map estimate"},
      {"caustic_k", SettingKind::Integer, "Nearest photons per caustic-map estimate"},
      {"global_radius", SettingKind::Real, "Maximum global-map search radius (scene units)"},
      {"caustic_radius", SettingKind::Real, "Maximum caustic-map search radius (scene units)"},
      {"gather_rays", SettingKind::Integer, "Final-gather rays per first diffuse hit"},
      {"volume_k", SettingKind::Integer,
       "In media: the volume photons' first radius holds this many of them (median over the map)"},
      {"volume_radius", SettingKind::Real, "In media: the volume photons' first radius (scene units; 0: from volume_k)"},
      {"volume_boundary", SettingKind::Boolean,
       "In media: normalise each volume photon's kernel over the part of its ball in its medium (no darkening at walls and medium boundaries)"},
      {"final_gather", SettingKind::Boolean,
       "Indirect light at the first diffuse hit by final gathering (true) or the global map's estimate (false; no caustic map); not given, the pilot measures both"},
      {"direct_samples", SettingKind::Integer, "Shadow-ray samples per first diffuse hit"},
      {"glossy_direct_samples", SettingKind::Integer, "Shadow-ray samples per glossy surface a camera path passes"},
      {"irradiance_stride", SettingKind::Integer, "Precompute irradiance at 1 in n global photons (0: off)"},
      {"glossy_threshold", SettingKind::Real, "Store photons and gather on glossy lobes at least this rough (alpha)"},
      {"caustic_threshold", SettingKind::Real,
       "Caustic photons pass delta surfaces and glossy ones smoother than this (alpha); rougher ones are final-gathered"},
      {"alpha", SettingKind::Real, "Progressive photon mapping and sppm: radius reduction, in (0, 1) (default 2/3)"},
      {"radius", SettingKind::Real, "First radius of every pixel (scene units)"},
      {"progressive", SettingKind::Boolean, "Fresh photon maps every pass, radii shrinking (consistent)"},
      {"path_fallback", SettingKind::Boolean,
       "Under a time budget, path trace the image where the pilot predicts path tracing's error below 1/1.5 of ours and no caustic photons are stored (default true)"},
      {"rr_depth", SettingKind::Integer, "Russian roulette starts after this many bounces"},
      {"hide_emitters", SettingKind::Boolean, "Directly visible emitters and the environment render black"},
  };
  return table;
}

const IntegratorPlugin* find_integrator_plugin(const std::string& name) {
  return find_plugin(integrator_plugins(), name);
}

const IntegratorSetting* find_integrator_setting(const std::string& key) {
  for (const IntegratorSetting& s : integrator_settings()) {
    if (key == s.key) return &s;
  }
  return nullptr;
}

std::string integrator_flag(const std::string& key) {
  std::string flag = "--" + key;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

std::string integrators_reading(const std::string& key) {
  std::string out;
  for (const IntegratorPlugin& p : integrator_plugins()) {
    if (p.reads(key)) out += (out.empty() ? "" : ", ") + std::string(p.name);
  }
  return out;
}

MonteCarloSettings read_monte_carlo(const Params& p, const RenderSettings& render) {
  MonteCarloSettings s;
  s.max_depth = render.max_depth;
  s.rr_depth = int(p.integer("rr_depth", s.rr_depth, 0, 1024));
  s.hide_emitters = p.boolean("hide_emitters", s.hide_emitters);
  return s;
}

void report_new_warnings(const std::vector<std::string>& fresh, std::vector<std::string>& seen, bool quiet) {
  for (const std::string& w : fresh) {
    // One warning per subject (the text before its colon): every progressive pass would
    // otherwise repeat "caustic photon map: only N of M stored" with its own N.
    const std::string subject = w.substr(0, w.find(':'));
    if (std::find(seen.begin(), seen.end(), subject) != seen.end()) continue;
    if (!quiet) std::cerr << "warning: " << w << "\n";
    seen.push_back(subject);
  }
}

std::string known_integrators() { return plugin_names(integrator_plugins()); }

std::string unknown_integrator(const std::string& name) {
  return "unknown integrator \"" + name + "\" (known: " + known_integrators() + ")";
}

std::unique_ptr<Integrator> create_integrator(const std::string& type, const JsonSource& settings,
                                              const RenderSettings& render) {
  const IntegratorPlugin* row = find_integrator_plugin(type);
  const SourceParams params(settings);
  if (!row) {
    const std::string message = unknown_integrator(type);
    // A type the scene file names: said with the file and the place.
    if (!settings.file.empty()) params.reader().fail(settings.pointer + "/type", message);
    throw InputError(message);
  }
  params.reader().check_object(settings.value, settings.pointer, row->keys);
  return row->create(params.params(), render);
}

}  // namespace caustica
