// `caustica converge`: equal-time renders of several integrators, error against a reference
// at checkpoints, and a report folder (CSV, images, error maps, index.html).
#pragma once
#include <optional>
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
};

int run_converge(const ConvergeArgs& args);
// The CSV text for the rows: header "integrator,seconds,passes,rmse,relmse", and a last column
// "relmse_floor_free" (relmse - floor) when the reference's floor is known.
std::string convergence_csv(const std::vector<ConvergeRow>& rows, std::optional<double> floor = std::nullopt);
// 1, 2, 4, ... below `time`, and `time` itself.
std::vector<double> default_checkpoints(double time);

}  // namespace caustica
