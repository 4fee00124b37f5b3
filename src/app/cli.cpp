// Command line (CLI11): `caustica render SCENE [options]`.
#include "app/cli.h"
#include <CLI/CLI.hpp>
#include <csignal>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <cmath>
#include <iterator>
#include <optional>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include "app/compare_command.h"
#include "app/render_command.h"
#include "core/json_reader.h"
#include "trace/integrator.h"

namespace caustica {

int run_cli(int argc, char** argv) {
  CLI::App app{"Caustica: a photon-mapping renderer (Jensen's two-pass method) with a path tracer to compare against"};
  app.set_version_flag("--version", std::string("caustica ") + CAUSTICA_VERSION);
  app.require_subcommand(1);

  RenderArgs args;
  CLI::App* render = app.add_subcommand("render", "Render a scene file to an image");
  render->add_option("scene", args.scene, "Scene file (JSON, see docs/scene-format.md)")->required();
  render->add_option("-o,--output", args.output, "Output image (.png, .exr, .hdr, .pfm); default: SCENE_NAME.png");
  render->add_option("--integrator", args.integrator, "Integrator: " + [] {
    std::string s;
    for (const auto& n : integrator_names()) s += (s.empty() ? "" : ", ") + n;
    return s;
  }());
  render->add_option("--spp", args.spp, "Samples per pixel")->check(CLI::Range(1, 1 << 24));
  render->add_option("--time", args.time, "Time budget in seconds: render whole passes until it is spent")
      ->check(CLI::PositiveNumber);
  render->add_option("--threads", args.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
  render->add_option("--seed", args.seed, "Random seed");
  render->add_option("--width", args.width, "Image width in pixels")->check(CLI::Range(1, 16384));
  render->add_option("--height", args.height, "Image height in pixels")->check(CLI::Range(1, 16384));
  render->add_option("--max-depth", args.max_depth, "Maximum path length")->check(CLI::Range(1, 1024));
  render->add_option("--exposure", args.exposure, "Exposure in stops for PNG output")->check(CLI::Range(-30.0, 30.0));
  render->add_flag("-q,--quiet", args.quiet, "No progress bar and no statistics");
  render->add_option("--reference", args.reference, "Print error figures against this reference image at the end");

  // Photon-mapping settings (integrators photon and photon-direct); each maps to a settings key.
  struct PhotonFlag {
    const char* flag;
    const char* key;
    const char* help;
    bool real;
  };
  static const PhotonFlag photon_flags[] = {
      {"--photons", "photons", "Photons stored in the global map", false},
      {"--caustic-photons", "caustic_photons", "Photons stored in the caustic map", false},
      {"--global-k", "global_k", "Nearest photons per global-map estimate", false},
      {"--caustic-k", "caustic_k", "Nearest photons per caustic-map estimate", false},
      {"--global-radius", "global_radius", "Maximum global-map search radius (scene units)", true},
      {"--caustic-radius", "caustic_radius", "Maximum caustic-map search radius (scene units)", true},
      {"--gather-rays", "gather_rays", "Final-gather rays per first diffuse hit", false},
      {"--direct-samples", "direct_samples", "Shadow-ray samples per first diffuse hit", false},
      {"--irradiance-stride", "irradiance_stride", "Precompute irradiance at every n-th global photon (0: off)", false},
  };
  std::vector<std::pair<const PhotonFlag*, CLI::Option*>> photon_options;
  static std::vector<double> photon_values(std::size(photon_flags));
  for (size_t i = 0; i < std::size(photon_flags); ++i) {
    const PhotonFlag& f = photon_flags[i];
    CLI::Option* o = render->add_option(f.flag, photon_values[i], f.help)->group("Photon mapping");
    o->check(CLI::NonNegativeNumber);
    photon_options.emplace_back(&f, o);
  }

  CompareArgs cargs;
  CLI::App* compare = app.add_subcommand("compare", "Error figures of an image against a reference");
  compare->add_option("image", cargs.image, "Image to judge (.exr, .hdr, .pfm, .png)")->required();
  compare->add_option("reference", cargs.reference, "Reference image")->required();
  compare->add_option("--diff", cargs.diff, "Write a false-colour map of the relative error (with a colour bar)");
  compare->add_flag("--json", cargs.json, "Print the figures as one JSON object");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;
  }
  for (size_t i = 0; i < photon_options.size(); ++i) {
    const PhotonFlag& f = *photon_options[i].first;
    if (photon_options[i].second->count() == 0) continue;
    const double v = photon_values[i];
    if (!f.real && v != std::floor(v)) {
      std::cerr << "error: " << f.flag << " " << v << ": expected a whole number\n";
      return 1;
    }
    args.integrator_overrides.emplace_back(f.key, f.real ? nlohmann::json(v) : nlohmann::json(int64_t(v)));
  }
  try {
    if (render->parsed()) return run_render(args);
    if (compare->parsed()) return run_compare(cargs);
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}

}  // namespace caustica
