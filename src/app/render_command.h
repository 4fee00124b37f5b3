// `caustica render`: load, override from the command line, render, write, report.
#pragma once
#include <optional>
#include <string>

namespace caustica {

struct RenderArgs {
  std::string scene, output, integrator;
  std::optional<int> spp, threads, width, height, max_depth;
  std::optional<uint64_t> seed;
  std::optional<double> time;
  float exposure = 0.0f;
  bool quiet = false;
};

int run_render(const RenderArgs& args);

}  // namespace caustica
