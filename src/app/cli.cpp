// Command line (CLI11): `caustica render SCENE [options]`.
#include "app/cli.h"
#include <CLI/CLI.hpp>
#include <csignal>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <tbb/global_control.h>
#include <tbb/info.h>
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

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;
  }
  try {
    if (render->parsed()) return run_render(args);
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
