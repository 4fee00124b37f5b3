// `caustica render`: load, override from the command line, render, write, report.
#pragma once
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include "app/scene_setup.h"

namespace caustica {

struct RenderArgs {
  SceneOptions common;
  std::string output, integrator, reference;
  std::optional<double> time;
  float exposure = 0.0f;
  bool aov = false;
};

int run_render(const RenderArgs& args);

}  // namespace caustica
