// `caustica converge`: equal-time renders of several integrators, error against a reference
// at checkpoints, and a report folder (CSV, images, error maps, index.html).
#pragma once
#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>
#include "app/scene_setup.h"
#include "trace/render.h"

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

// How converge_integrator runs: quiet, the processes sharing the passes, a cancel flag, and a
// call for each row as it is measured (for progress lines).
struct ConvergeRunOptions {
  bool quiet = true;
  const Cluster* cluster = nullptr;
  const std::atomic<bool>* cancel = nullptr;
  std::function<void(const ConvergeRow&)> on_row;
};
// One integrator's equal-time run: preprocess, then passes until `time` seconds (preprocess
// included) are spent, its mean image measured against `reference` at the first pass past each
// of the sorted `checkpoints` and at the end. Appends its rows; returns the final image (empty
// on ranks other than 0, or without a completed pass) and the render's statistics.
Image converge_integrator(Scene& scene, Integrator& integrator, const std::string& name, double time,
                          const std::vector<double>& checkpoints, const Image& reference,
                          const ConvergeRunOptions& options, std::vector<ConvergeRow>& rows, RenderStats* stats = nullptr,
                          double* preprocess_seconds = nullptr);
// The CSV text for the rows: header "integrator,seconds,passes,rmse,relmse", and a last column
// "relmse_floor_free" (relmse - floor) when the reference's floor is known.
std::string convergence_csv(const std::vector<ConvergeRow>& rows, std::optional<double> floor = std::nullopt);
// 1, 2, 4, ... below `time`, and `time` itself.
std::vector<double> default_checkpoints(double time);

}  // namespace caustica
