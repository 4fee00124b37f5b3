// `caustica converge`.
#include "app/converge_command.h"
#include "app/stop_signals.h"
#include <algorithm>
#include <cmath>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <tbb/global_control.h>
#include "app/compare_command.h"
#include "app/report.h"
#include "core/metrics.h"
#include "core/rng.h"
#include "io/image_io.h"
#include "trace/render.h"

namespace caustica {
namespace fs = std::filesystem;

std::vector<double> default_checkpoints(double time) {
  std::vector<double> c;
  for (double t = 1; t < time; t *= 2) c.push_back(t);
  c.push_back(time);
  return c;
}

std::string convergence_csv(const std::vector<ConvergeRow>& rows, std::optional<double> floor) {
  std::ostringstream s;
  s << "integrator,seconds,passes,rmse,relmse" << (floor ? ",relmse_floor_free" : "") << "\n" << std::setprecision(9);
  for (const ConvergeRow& r : rows) {
    s << r.integrator << "," << r.seconds << "," << r.passes << "," << r.rmse << "," << r.relmse;
    if (floor) s << "," << r.relmse - *floor;
    s << "\n";
  }
  return s.str();
}

Image converge_integrator(Scene& scene, Integrator& integ, const std::string& name, double time,
                          const std::vector<double>& checkpoints, const Image& reference,
                          const ConvergeRunOptions& o, std::vector<ConvergeRow>& rows, RenderStats* stats_out,
                          double* preprocess_seconds) {
  const int rank = o.cluster ? o.cluster->rank() : 0, ranks = o.cluster ? o.cluster->size() : 1;
  const auto t0 = std::chrono::steady_clock::now();
  integ.preprocess(scene, {scene.render.seed, o.quiet, o.cancel, rank, scene.render.spp, time, ranks});
  const double pre = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const size_t first = rows.size();
  auto record = [&](double seconds, long passes, const Image& mean) {
    const ErrorMetrics m = compare_images(mean, reference);
    rows.push_back({name, seconds, passes, m.rmse, m.relmse});
    if (o.on_row) o.on_row(rows.back());
  };
  size_t next = 0;
  RenderOptions options;
  options.job = render_job(scene.render, std::max(1e-3, time - pre));
  options.quiet = o.quiet;
  options.cluster = o.cluster;
  // A mean image at the first pass past each checkpoint (on rank 0's clock).
  options.want_pass = [&](double seconds) { return next < checkpoints.size() && pre + seconds >= checkpoints[next]; };
  options.on_pass = [&](int passes, double seconds, const Image& mean) {
    const double t = pre + seconds;
    record(t, passes, mean);
    while (next < checkpoints.size() && t >= checkpoints[next]) ++next;
  };
  options.cancel = o.cancel;
  RenderStats stats;
  Image image = render_image(scene, integ, options, stats);
  if (rank == 0 && stats.passes > 0 && (rows.size() == first || rows.back().passes != stats.passes)) {
    record(pre + stats.seconds, stats.passes, image);
  }
  if (stats_out) *stats_out = stats;
  if (preprocess_seconds) *preprocess_seconds = pre;
  return image;
}

int run_converge(const ConvergeArgs& args) {
  // Under MPI each integrator's passes are split among the ranks; rank 0 measures and writes.
  const Cluster& cluster = Cluster::world();
  const bool root = cluster.root();
  if (root) {
    std::error_code ec;
    fs::create_directories(args.out_dir, ec);
    if (!fs::is_directory(args.out_dir)) throw InputError(args.out_dir + ": cannot create the output folder");
  }
  const Reference combined = read_references(args.references);
  const Image& reference = combined.mean;
  const bool has_floor = combined.has_floor();
  const std::string reference_name = describe_references(args.references);
  LoadedScene loaded = load_scene_with(args.common);
  Scene& scene = *loaded.scene;
  // Without --seed, a seed derived from the scene's: a reference rendered with the scene's
  // own seed would otherwise share its first passes with ours.
  if (!args.common.seed) scene.render.seed = hash_seed(scene.render.seed, 0x636f6e76);  // "conv"
  if (!args.common.width && !args.common.height) {
    // Follow the reference's size unless the command line says otherwise.
    scene.render.width = reference.width;
    scene.render.height = reference.height;
    scene.camera.set_resolution(reference.width, reference.height);
  }
  if (reference.width != scene.render.width || reference.height != scene.render.height) {
    throw InputError(reference_name + ": reference is " + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height) + ", the render " + std::to_string(scene.render.width) + "x" +
                     std::to_string(scene.render.height));
  }
  std::vector<double> checkpoints = args.checkpoints.empty() ? default_checkpoints(args.time) : args.checkpoints;
  std::sort(checkpoints.begin(), checkpoints.end());
  // Create every integrator first, so that a bad name fails before any rendering.
  std::vector<std::unique_ptr<Integrator>> integrators;
  for (const std::string& name : args.integrators) integrators.push_back(integrator_for(loaded, name, args.common, true));
  {
    std::ostringstream command_settings;
    command_settings << "converge " << reference_name << " time=" << args.time << std::setprecision(17);
    for (const std::string& name : args.integrators) command_settings << " " << name;
    for (double c : checkpoints) command_settings << " @" << c;
    std::vector<const Integrator*> all;
    for (const auto& integ : integrators) all.push_back(integ.get());
    check_ranks_agree(args.common, command_settings.str(), all);
  }
  const bool quiet = args.common.quiet || !root;

  check_film_memory(scene.render.width, scene.render.height, false);
  const int threads = thread_count(args.common);
  tbb::global_control control(tbb::global_control::max_allowed_parallelism, size_t(threads));
  std::vector<ConvergeRow> rows;
  ReportData report;
  report.title = fs::path(args.common.scene).filename().string() + ": " + std::to_string(int(args.time)) +
                 " s per integrator";
  report.facts = {{"scene", args.common.scene},
                  {"reference", reference_name},
                  {"resolution", std::to_string(scene.render.width) + "x" + std::to_string(scene.render.height)},
                  {"threads", std::to_string(threads) + (cluster.distributed() ? " per rank, " +
                                  std::to_string(cluster.size()) + " MPI ranks" : "")},
                  {"seed", std::to_string(scene.render.seed)}};
  if (has_floor) {
    std::ostringstream f;
    f << std::scientific << std::setprecision(3) << combined.floor
      << " (relMSE of the references' mean, from their spread; subtracted in relmse_floor_free)";
    report.facts.emplace_back("reference floor", f.str());
    if (!quiet) std::cerr << "reference floor: " << f.str() << "\n";
  }
  if (root) write_image((fs::path(args.out_dir) / "reference.png").string(), reference);
  report.images.push_back({"reference", "reference.png"});
  std::vector<ReportImage> error_images;

  // Ctrl-C or SIGTERM ends the integrator being run after its completed passes; the figures so
  // far are written (the report says it was interrupted), and the exit code is 128 + the signal.
  StopSignals stop_signals;
  bool interrupted = false;
  for (size_t i = 0; i < integrators.size() && !interrupted; ++i) {
    Integrator& integ = *integrators[i];
    const std::string name = args.integrators[i];
    ConvergeRunOptions run;
    run.quiet = quiet;
    run.cluster = &cluster;
    run.cancel = &StopSignals::flag();
    run.on_row = [&](const ConvergeRow& r) {
      if (quiet) return;
      std::cerr << name << ": " << std::fixed << std::setprecision(1) << r.seconds << " s, " << r.passes
                << " passes, relMSE " << std::scientific << std::setprecision(3) << r.relmse;
      if (has_floor) std::cerr << " (" << r.relmse - combined.floor << " without the floor)";
      std::cerr << std::defaultfloat << "\n";
    };
    const size_t first_row = rows.size();
    RenderStats stats;
    double pre = 0;
    const Image image = converge_integrator(scene, integ, name, args.time, checkpoints, reference, run, rows, &stats, &pre);
    interrupted = stats.interrupted;
    if (interrupted) {
      std::string left;
      for (size_t k = i + 1; k < integrators.size(); ++k) left += (left.empty() ? "; not run: " : ", ") + args.integrators[k];
      report.facts.emplace_back("interrupted", "during " + name + ", after " + std::to_string(stats.passes) + " passes" + left);
      if (!quiet && root) std::cerr << "interrupted during " << name << left << "\n";
    }
    if (!root || stats.passes == 0) continue;
    const double total = pre + stats.seconds;
    ReportSeries series{name, {}};
    for (size_t r = first_row; r < rows.size(); ++r) series.points.push_back({rows[r].seconds, rows[r].relmse, rows[r].rmse, rows[r].passes});
    report.series.push_back(series);
    // The late log-log slope of the raw figures, and of those without the reference's floor.
    auto add_rate = [&](const ReportSeries& s, const std::string& what, const std::string& fact) {
      const double slope = convergence_slope(s);
      if (!std::isfinite(slope)) return;
      std::ostringstream rate;
      rate << what << " ~ t^" << std::fixed << std::setprecision(2) << slope << " from " << std::setprecision(1)
           << 0.25 * total << " s on" << (slope > -0.2 ? " (flattening: a bias floor)" : "");
      report.facts.emplace_back(name + fact, rate.str());
      if (!quiet) std::cerr << name << ": " << rate.str() << "\n";
    };
    add_rate(series, "relMSE", " rate");
    if (has_floor) {
      ReportSeries floor_free = series;
      for (ReportPoint& p : floor_free.points) p.relmse -= combined.floor;
      // Figures at or below the floor have no logarithm: the slope would skip them and mislead.
      if (std::all_of(floor_free.points.begin(), floor_free.points.end(), [](const ReportPoint& p) { return p.relmse > 0; })) {
        add_rate(floor_free, "relMSE - floor", " rate without the floor");
      } else {
        report.facts.emplace_back(name + " rate without the floor", "none: some figures are within the reference's floor");
      }
    }
    // Variants such as photon:progressive=false get file names without ':' and '='.
    std::string file = name;
    std::replace_if(file.begin(), file.end(), [](char c) { return c == ':' || c == '=' || c == '/'; }, '_');
    const std::string stem = (fs::path(args.out_dir) / file).string();
    write_image(stem + ".exr", image);
    write_image(stem + ".png", image);
    write_image(stem + "-error.png", error_map(image, reference));
    report.images.push_back({name, file + ".png"});
    error_images.push_back({name + " error", file + "-error.png"});
    report.facts.emplace_back(name, std::to_string(stats.passes) + " passes in " + std::to_string(total) + " s (" +
                                        std::to_string(pre) + " s preprocess)");
  }
  // The handlers stay until the files are written (a signal meanwhile waits for them). The other
  // ranks wait for rank 0's files: an exit code other than 0 makes mpirun end the whole job.
  if (!root) {
    cluster.barrier();
    return interrupted ? StopSignals::exit_code() : 0;
  }
  report.images.insert(report.images.end(), error_images.begin(), error_images.end());
  write_file_atomically((fs::path(args.out_dir) / "convergence.csv").string(), convergence_csv(rows, has_floor ? std::optional<double>(combined.floor) : std::nullopt), "CSV");
  write_report(args.out_dir, report);
  if (!quiet) std::cout << "wrote " << (fs::path(args.out_dir) / "index.html").string() << "\n";
  cluster.barrier();
  return interrupted || StopSignals::stopped() ? StopSignals::exit_code() : 0;
}

}  // namespace caustica
