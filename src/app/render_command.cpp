// `caustica render`.
#include "app/render_command.h"
#include <algorithm>
#include <atomic>
#include <csignal>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include "app/compare_command.h"
#include "core/json_reader.h"
#include "core/scene_loader.h"
#include "trace/progress.h"
#include "trace/render.h"

namespace caustica {
namespace {

std::atomic<bool> g_interrupted{false};
extern "C" void on_sigint(int) { g_interrupted.store(true); }

}  // namespace

int run_render(const RenderArgs& args) {
  LoadedScene loaded = load_scene(args.scene);
  Scene& scene = *loaded.scene;
  for (const std::string& w : loaded.warnings) std::cerr << "warning: " << w << "\n";

  RenderSettings& rs = scene.render;
  if (args.width) rs.width = *args.width;
  if (args.height) rs.height = *args.height;
  if (args.spp) rs.spp = *args.spp;
  if (args.seed) rs.seed = *args.seed;
  if (args.max_depth) rs.max_depth = *args.max_depth;
  scene.camera.set_resolution(rs.width, rs.height);

  const std::string output = !args.output.empty()
      ? args.output
      : std::filesystem::path(args.scene).stem().string() + ".png";
  check_output_path(output);
  Image reference;
  if (!args.reference.empty()) {
    reference = read_image(args.reference);
    if (reference.width != rs.width || reference.height != rs.height) {
      throw InputError(args.reference + ": reference is " + std::to_string(reference.width) + "x" +
                       std::to_string(reference.height) + ", the render " + std::to_string(rs.width) + "x" +
                       std::to_string(rs.height));
    }
  }

  std::string type = scene.integrator_type;
  JsonSource settings = scene.integrator_settings;
  if (!args.integrator.empty() && args.integrator != type) {
    // The scene's settings were written for another integrator: use the defaults.
    if (!settings.value.empty() && !args.quiet) {
      std::cerr << "note: --integrator " << args.integrator << " replaces the scene's \"" << type
                << "\"; its settings in " << settings.pointer << " are not used\n";
    }
    type = args.integrator;
    settings.value = nlohmann::json::object();
  }
  for (const auto& kv : args.integrator_overrides) {
    std::string flag = "--" + kv.first;
    std::replace(flag.begin(), flag.end(), '_', '-');
    const bool gather_only = kv.first == "gather_rays" || kv.first == "direct_samples" || kv.first == "irradiance_stride";
    if ((type != "photon" && type != "photon-direct") || (type == "photon-direct" && gather_only)) {
      throw InputError(flag + " does not apply to integrator \"" + type + "\"");
    }
    settings.value[kv.first] = kv.second;
  }
  std::unique_ptr<Integrator> integrator = create_integrator(type, settings, rs);

  const int threads = args.threads ? *args.threads : tbb::info::default_concurrency();
  tbb::global_control control(tbb::global_control::max_allowed_parallelism, size_t(threads));

  g_interrupted = false;
  auto previous = std::signal(SIGINT, on_sigint);
  PreprocessContext pre{rs.seed, args.quiet};
  const auto t0 = std::chrono::steady_clock::now();
  integrator->preprocess(scene, pre);
  const double preprocess_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  RenderOptions options;
  options.spp = rs.spp;
  options.time_limit = args.time ? *args.time : 0.0;
  options.seed = rs.seed;
  options.quiet = args.quiet;
  options.cancel = &g_interrupted;
  RenderStats stats;
  Image image = g_interrupted ? Image(rs.width, rs.height) : render_image(scene, *integrator, options, stats);
  std::signal(SIGINT, previous);
  if (g_interrupted) stats.interrupted = true;
  write_image(output, image, args.exposure);

  if (!args.quiet) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(3);
    s << "scene: " << args.scene << " (" << loaded.triangle_count << " triangles, " << loaded.sphere_count
      << " spheres, " << scene.lights.size() << " lights)\n";
    s << "integrator: " << integrator->name() << "\n" << integrator->describe();
    s << "image: " << output << " (" << rs.width << "x" << rs.height << ")\n";
    s << "threads: " << threads << "\nseed: " << rs.seed << "\n";
    s << "preprocess time: " << preprocess_seconds << " s\n";
    s << "render time: " << stats.seconds << " s\n";
    s << "passes (spp): " << stats.passes << (stats.interrupted ? " (interrupted: passes completed so far)" : "")
      << "\n";
    s << "camera samples: " << stats.samples << "\n";
    s << std::setprecision(0);
    s << "samples per second: " << (stats.seconds > 0 ? stats.samples / stats.seconds : 0.0) << "\n";
    s << "rays: " << stats.rays << "\nrays per second: " << (stats.seconds > 0 ? stats.rays / stats.seconds : 0.0)
      << "\n";
    s << "bad samples (NaN/Inf/negative, dropped): " << stats.bad_samples << "\n";
    std::cout << s.str();
  }
  if (!args.reference.empty()) {
    const ErrorMetrics m = compare_images(image, reference, output, args.reference);
    if (!args.quiet) std::cout << "error against " << args.reference << ":\n";
    std::cout << format_metrics(m, false);
  }
  return stats.interrupted ? 130 : 0;
}

}  // namespace caustica
