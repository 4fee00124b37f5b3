// `caustica converge`: equal-time renders of several integrators, error against a reference
// at checkpoints, and a report folder (CSV, images, error maps, index.html).
#pragma once
#include <cmath>
#include <string>
#include <vector>
#include "app/scene_setup.h"

namespace caustica {

struct ConvergeArgs {
  SceneOptions common;
  std::vector<std::string> references;  // one image, or independent renders averaged
  std::string out_dir;
  std::vector<std::string> integrators;
  double time = 0;
  std::vector<double> checkpoints;  // empty: 1, 2, 4, ... up to time
};

struct ConvergeRow {
  std::string integrator;
  double seconds = 0;
  long passes = 0;
  double rmse = 0, relmse = 0;
  // relmse less the reference's floor, when the reference is several renders (NaN otherwise)
  double relmse_floor_free = std::nan("");
};

int run_converge(const ConvergeArgs& args);
// The CSV text for the rows: header "integrator,seconds,passes,rmse,relmse", and a last column
// "relmse_floor_free" with `floor_free` (the reference is several renders).
std::string convergence_csv(const std::vector<ConvergeRow>& rows, bool floor_free = false);
// 1, 2, 4, ... below `time`, and `time` itself.
std::vector<double> default_checkpoints(double time);

}  // namespace caustica
