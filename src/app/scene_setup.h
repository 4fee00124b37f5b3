// What render, converge and photons share: scene loading with command-line overrides, and
// the integrator chosen by the scene or by --integrator.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include <nlohmann/json.hpp>
#include "io/scene_loader.h"
#include "trace/integrator.h"

namespace caustica {

struct SceneOptions {
  std::string scene;
  std::optional<int> spp, threads, width, height, max_depth;
  std::optional<uint64_t> seed;
  // Integrator settings from flags such as --photons, by settings key (applied over the scene's).
  std::vector<std::pair<std::string, nlohmann::json>> integrator_overrides;
  bool quiet = false;
  MitsubaOptions mitsuba;  // -D and --ignore-unsupported
  std::string accel;       // --accel bvh|embree (empty: the scene's)
  std::string light_sampler;  // --light-sampler tree|power (empty: the scene's)
};

// Loads the scene (warnings to stderr) and applies the command line's render settings.
LoadedScene load_scene_with(const SceneOptions& options);

// Creates `type` (empty: the scene's integrator), which may carry settings:
// "photon:progressive=false:photons=50000" (values are JSON; a bare word is a string). The scene's integrator settings apply when
// the type is the scene's own; the overrides apply on top. With `lenient`, photon flags are
// skipped for integrators they do not apply to (converge compares several at once).
std::unique_ptr<Integrator> integrator_for(const LoadedScene& loaded, const std::string& type, const SceneOptions& options,
                                           bool lenient = false);

int thread_count(const SceneOptions& options);

// Under MPI (a no-op for one process): refuses integrators whose passes depend on one another,
// and ranks given different scene files (their bytes), scene options or `command_settings` (what
// the command adds: integrators, --time, ...). A refusal is an InputError on every rank.
void check_ranks_agree(const SceneOptions& options, const std::string& command_settings,
                       const std::vector<const Integrator*>& integrators);

}  // namespace caustica
