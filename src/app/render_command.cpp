// `caustica render`.
#include "app/render_command.h"
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <tbb/global_control.h>
#include "app/compare_command.h"
#include "app/stop_signals.h"
#include "io/image_io.h"
#include "io/json_reader.h"
#include "io/scene_loader.h"
#include "trace/progress.h"
#include "trace/render.h"

namespace caustica {
namespace {
// An AOV's file beside the main output: out.png -> out.photons.exr.
std::string aov_path(const std::string& output, const char* suffix) {
  const std::filesystem::path out(output);
  return (out.parent_path() / out.stem()).string() + suffix;
}
}  // namespace

int run_render(const RenderArgs& args) {
  LoadedScene loaded = load_scene_with(args.common);
  Scene& scene = *loaded.scene;
  const RenderSettings& rs = scene.render;

  const Cluster& cluster = Cluster::world();
  const std::string output = !args.output.empty()
      ? args.output
      : std::filesystem::path(args.common.scene).stem().string() + ".png";
  // Rank 0 alone writes the image and compares it: other machines need neither path.
  if (cluster.root()) check_output_path(output);
  Image reference;
  if (!args.reference.empty() && cluster.root()) {
    reference = read_image(args.reference);
    if (reference.width != rs.width || reference.height != rs.height) {
      throw InputError(args.reference + ": reference is " + std::to_string(reference.width) + "x" +
                       std::to_string(reference.height) + ", the render " + std::to_string(rs.width) + "x" +
                       std::to_string(rs.height));
    }
  }

  std::unique_ptr<Integrator> integrator = integrator_for(loaded, args.integrator, args.common);
  if (args.aov && !integrator->supports_aov()) {
    throw InputError("--aov needs a photon integrator (photon or photon-direct), not \"" + integrator->name() + "\"");
  }
  if (args.aov && cluster.root()) {
    for (const char* aov : {".photons.exr", ".radius.exr"}) check_output_file(aov_path(output, aov));
  }
  // Under mpirun: every rank must render the same image, and the integrator's passes must not
  // depend on one another.
  std::ostringstream command_settings;
  command_settings << "render " << integrator->name() << " time=" << (args.time ? *args.time : 0.0)
                   << " aov=" << args.aov;
  check_ranks_agree(args.common, command_settings.str(), {integrator.get()});

  check_film_memory(rs.width, rs.height, args.aov);
  const int threads = thread_count(args.common);
  tbb::global_control control(tbb::global_control::max_allowed_parallelism, size_t(threads));

  // Ctrl-C and SIGTERM stop the render (the passes done are kept) and, while the image is being
  // written, wait for it: the handlers stay until the outputs are in place (issue 23).
  StopSignals stop_signals;
  const bool quiet = args.common.quiet || !cluster.root();  // one progress bar and report: rank 0's
  const RenderJob job = render_job(rs, args.time ? *args.time : 0.0);
  PreprocessContext pre{job.seed, quiet, &StopSignals::flag(), cluster.rank(), job.passes, job.time_budget, cluster.size()};
  const auto t0 = std::chrono::steady_clock::now();
  integrator->preprocess(scene, pre);
  const double preprocess_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  RenderOptions options;
  options.job = job;
  options.quiet = quiet;
  options.cluster = &cluster;
  options.cancel = &StopSignals::flag();
  options.aov = args.aov;
  RenderStats stats;
  std::vector<Image> aovs;
  // Under MPI every rank enters the render, which agrees on a stop (a rank's preprocess may have
  // been interrupted while the others' was not).
  Image image = StopSignals::stopped() && !cluster.distributed() ? Image(rs.width, rs.height)
                                                        : render_image(scene, *integrator, options, stats, &aovs);
  if (StopSignals::stopped()) stats.interrupted = true;
  // The shell's convention: 128 + the signal (130 for SIGINT, 143 for SIGTERM).
  const int interrupted_code = StopSignals::exit_code();
  // Rank 0 writes the image of all ranks. The others wait until it has: a rank that exits with
  // an error code (an interrupted one does) makes mpirun kill the rest of the job.
  if (!cluster.root()) {
    stop_signals.restore();  // nothing to write here
    cluster.barrier();
    return stats.interrupted ? interrupted_code : 0;
  }
  if (stats.interrupted && stats.passes == 0) {
    std::cerr << "interrupted before the first pass was complete: no image written\n";
    stop_signals.restore();
    cluster.barrier();
    return interrupted_code;
  }
  // The image and its AOVs appear together or not at all.
  AtomicFileSet outputs;
  write_image_to(outputs.add(output), image, args.exposure);
  const bool with_aovs = args.aov && aovs.size() == 2;
  if (with_aovs) {
    // Beside the main output: photon counts (R global, G caustic) and estimate radii, linear EXR.
    write_image_to(outputs.add(aov_path(output, ".photons.exr")), aovs[0]);
    write_image_to(outputs.add(aov_path(output, ".radius.exr")), aovs[1]);
  }
  outputs.commit("image");
  stop_signals.restore();
  if (with_aovs && !args.common.quiet) {
    std::cout << "aov: " << aov_path(output, ".photons.exr") << ", " << aov_path(output, ".radius.exr") << "\n";
  }
  cluster.barrier();

  if (!args.common.quiet) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(3);
    s << "scene: " << args.common.scene << " (" << loaded.triangle_count << " triangles, " << loaded.sphere_count
      << " spheres, " << scene.lights.size() << " lights)\n";
    s << "ray casting: " << scene.accel().name() << " (" << std::setprecision(1)
      << double(scene.accel().memory_bytes()) / (1 << 20) << " MiB)\n" << std::setprecision(3);
    if (scene.lights.size() > 1) s << "light sampler: " << light_sampler_name(rs.light_sampler) << "\n";
    s << "integrator: " << integrator->name() << "\n" << integrator->describe();
    if (cluster.distributed()) s << "(the integrator's figures above are rank 0's own; those below are all ranks')\n";
    s << "image: " << output << " (" << rs.width << "x" << rs.height << ")\n";
    s << "threads: " << threads << (cluster.distributed() ? " per rank" : "") << "\n";
    if (cluster.distributed()) s << "MPI ranks: " << cluster.size() << " (rays and samples: all ranks)\n";
    s << "seed: " << rs.seed << "\n";
    s << "preprocess time: " << preprocess_seconds << " s\n";
    s << "render time: " << stats.seconds << " s\n";
    if (cluster.distributed()) s << "image gathering (in the render time): " << stats.gather_seconds << " s\n";
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
  if (stats.bad_samples > 0 && cluster.root()) {
    std::cerr << "warning: " << stats.bad_samples << " of " << stats.samples
              << " camera samples were NaN, infinite or negative and were left out: the image is darker where they fell\n";
  }
  if (!args.reference.empty()) {
    const ErrorMetrics m = compare_images(image, reference, output, args.reference);
    if (!args.common.quiet) std::cout << "error against " << args.reference << ":\n";
    std::cout << format_metrics(m, false);
  }
  // A signal while the outputs were written waited for them; it still ends with its code.
  return stats.interrupted || StopSignals::stopped() ? StopSignals::exit_code() : 0;
}

}  // namespace caustica
