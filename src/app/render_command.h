// `caustica render`: load, override from the command line, render, write, report.
#pragma once
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include <nlohmann/json.hpp>

namespace caustica {

struct RenderArgs {
  std::string scene, output, integrator, reference;
  std::optional<int> spp, threads, width, height, max_depth;
  std::optional<uint64_t> seed;
  std::optional<double> time;
  // Integrator settings from flags such as --photons, by settings key (applied over the scene's).
  std::vector<std::pair<std::string, nlohmann::json>> integrator_overrides;
  float exposure = 0.0f;
  bool quiet = false;
};

int run_render(const RenderArgs& args);

}  // namespace caustica
