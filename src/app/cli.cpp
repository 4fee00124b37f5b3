// Command line (CLI11): `caustica render | compare | converge | photons`.
#include "app/cli.h"
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <new>
#include "app/compare_command.h"
#include "app/converge_command.h"
#include "app/photons_command.h"
#include "app/plugins_command.h"
#include "app/render_command.h"
#include "core/memory.h"
#include "io/json_reader.h"
#include "trace/cluster.h"
#include "trace/integrator.h"

namespace caustica {
namespace {

// A number that is finite: NaN and infinities pass CLI11's range checks (every comparison with
// NaN is false), so they are refused here.
const CLI::Validator kFinite(
    [](std::string& text) {
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      return end != text.c_str() && std::isfinite(v) ? std::string() : "expected a finite number, not " + text;
    },
    "FINITE");

// Number checks with messages a person can read (CLI11's own print a 300-digit bound).
CLI::Validator number_check(const char* name, const char* expected, bool (*ok)(double)) {
  return CLI::Validator(
      [expected, ok](std::string& text) {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        return end != text.c_str() && *end == '\0' && ok(v) ? std::string() : std::string("expected ") + expected + ", not " + text;
      },
      name);
}
const CLI::Validator kNonNegative = number_check("NONNEGATIVE", "a number >= 0", [](double v) { return v >= 0.0; });
const CLI::Validator kPositive = number_check("POSITIVE", "a number > 0", [](double v) { return v > 0.0; });
// Digits only, at most 2^64 - 1 (strtoull alone would take "-1" as 2^64 - 1).
const CLI::Validator kSeed(
    [](std::string& text) {
      errno = 0;
      const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
      if (digits) std::strtoull(text.c_str(), nullptr, 10);
      return digits && errno == 0 ? std::string() : "expected a whole number from 0 to 2^64 - 1, not " + text;
    },
    "SEED");

// The options every scene-reading subcommand takes.
struct SceneFlags {
  SceneOptions* options = nullptr;
  // One entry per integrator_settings() row: a number's value, or a boolean's --key / --no-key.
  std::vector<double> values;
  std::vector<CLI::Option*> given;
  std::vector<int> on, off;
  std::vector<std::string> defines;

  void add(CLI::App* cmd, SceneOptions& o, bool with_spp) {
    options = &o;
    cmd->add_option("scene", o.scene, "Scene file: JSON (docs/scene-format.md) or Mitsuba XML (docs/mitsuba.md)")->required();
    cmd->add_option("-D", defines, "Mitsuba scenes: set a parameter, -D name=value (wins over <default>)")
        ->group("Mitsuba scenes")
        ->allow_extra_args(false);
    cmd->add_flag("--ignore-unsupported", o.mitsuba.ignore_unsupported,
                  "Mitsuba scenes: skip or replace unsupported plugins with a warning instead of failing")
        ->group("Mitsuba scenes");
    if (with_spp) cmd->add_option("--spp", o.spp, "Samples per pixel")->check(CLI::Range(1, 1 << 24));
    cmd->add_option("--threads", o.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
    cmd->add_option("--seed", o.seed, "Random seed (0 to 2^64 - 1)")->check(kSeed);
    cmd->add_option("--width", o.width, "Image width in pixels")->check(CLI::Range(1, 16384));
    cmd->add_option("--height", o.height, "Image height in pixels")->check(CLI::Range(1, 16384));
    cmd->add_option("--max-depth", o.max_depth, "Maximum path length")->check(CLI::Range(0, 1024));
    cmd->add_option("--accel", o.accel, "Ray casting: embree (the default where built) or bvh (our own)")
        ->check(CLI::IsMember({"bvh", "embree"}));
    cmd->add_option("--light-sampler", o.light_sampler,
                    "How shadow rays choose a light: tree (by importance at the point, the default) or power")
        ->check(CLI::IsMember({"tree", "power"}));
    cmd->add_flag("-q,--quiet", o.quiet, "No progress bar and no statistics");
    // The integrators' settings, from their registry: each flag says which integrators read it.
    const std::vector<IntegratorSetting>& settings = integrator_settings();
    values.assign(settings.size(), 0.0);
    given.assign(settings.size(), nullptr);
    on.assign(settings.size(), 0);
    off.assign(settings.size(), 0);
    for (size_t i = 0; i < settings.size(); ++i) {
      const IntegratorSetting& s = settings[i];
      const std::string help = std::string(s.help) + " (" + integrators_reading(s.key) + ")";
      const std::string flag = integrator_flag(s.key);
      if (s.kind == SettingKind::Boolean) {
        given[i] = cmd->add_flag(flag, on[i], help)->group("Integrator settings");
        cmd->add_flag("--no-" + flag.substr(2), off[i], "The opposite of " + flag)
            ->group("Integrator settings")
            ->excludes(given[i]);
      } else {
        given[i] = cmd->add_option(flag, values[i], help)
                       ->group("Integrator settings")
                       ->type_name(s.kind == SettingKind::Integer ? "INT" : "FLOAT")
                       ->check(kFinite & kNonNegative);
      }
    }
  }
  // Moves the integrator flags given into options->integrator_overrides, and -D into the Mitsuba options.
  void collect() const {
    for (const std::string& d : defines) {
      const size_t eq = d.find('=');
      if (eq == std::string::npos || eq == 0) throw InputError("-D " + d + ": expected name=value");
      options->mitsuba.xml.defines.emplace_back(d.substr(0, eq), d.substr(eq + 1));
    }
    const std::vector<IntegratorSetting>& settings = integrator_settings();
    for (size_t i = 0; i < settings.size(); ++i) {
      const IntegratorSetting& s = settings[i];
      if (s.kind == SettingKind::Boolean) {
        if (on[i] || off[i]) options->integrator_overrides.emplace_back(s.key, on[i] > 0);
        continue;
      }
      if (given[i]->count() == 0) continue;
      const double v = values[i];
      if (s.kind == SettingKind::Integer && v != std::floor(v)) {
        throw InputError(integrator_flag(s.key) + " " + std::to_string(v) + ": expected a whole number");
      }
      // Beyond 2^53 a double no longer holds every whole number (and past 2^63 none fits the
      // settings' integers): no setting goes anywhere near it.
      if (s.kind == SettingKind::Integer && v > 9007199254740992.0) {
        throw InputError(integrator_flag(s.key) + " " + given[i]->as<std::string>() + ": out of range");
      }
      options->integrator_overrides.emplace_back(s.key, s.kind == SettingKind::Real ? nlohmann::json(v) : nlohmann::json(int64_t(v)));
    }
  }
};

// Each item of a comma-separated list of integrators: a name, with settings after it
// (photon:progressive=false, checked when the integrator is made), or only settings for the
// scene's own integrator (:max_depth=3).
const CLI::Validator kIntegratorName(
    [](std::string& item) {
      if (item.empty()) return std::string("an empty integrator name (write e.g. photon,path)");
      if (item[0] == '-') {
        // CLI11 lets a list that ends in its delimiter go on in the next argument.
        return "expected integrator names (e.g. photon,path), not \"" + item + "\"";
      }
      const std::string name = item.substr(0, item.find(':'));
      if (name.empty()) return std::string();
      if (find_integrator_plugin(name)) return std::string();
      return unknown_integrator(name);
    },
    "INTEGRATOR");

}  // namespace

int run_cli(int argc, char** argv) {
  CLI::App app{"Caustica: a photon-mapping renderer (Jensen's two-pass method) with a path tracer to compare against"};
  app.set_version_flag("--version", std::string("caustica ") + CAUSTICA_VERSION);
  app.require_subcommand(1);

  RenderArgs args;
  SceneFlags render_flags;
  CLI::App* render = app.add_subcommand("render", "Render a scene file to an image");
  render_flags.add(render, args.common, true);
  render->add_option("-o,--output", args.output, "Output image (.png, .exr, .hdr, .pfm); default: SCENE_NAME.png");
  render->add_option("--integrator", args.integrator, "Integrator: " + known_integrators());
  render->add_option("--time", args.time, "Time budget in seconds: render whole passes until it is spent")
      ->check(kFinite & kPositive);
  render->add_option("--exposure", args.exposure, "Exposure in stops for PNG output")
      ->check(kFinite & CLI::Range(-30.0, 30.0));
  render->add_option("--reference", args.reference, "Print error figures against this reference image at the end");
  render->add_flag("--aov", args.aov, "photon integrators: also write per-pixel photon count and gather radius images");

  CompareArgs cargs;
  CLI::App* compare = app.add_subcommand("compare", "Error figures of an image against a reference");
  compare->add_option("image", cargs.image, "Image to judge (.exr, .hdr, .pfm, .png)")->required();
  compare->add_option("reference", cargs.references,
                      "Reference image; several independent renders (other seeds) are compared against as "
                      "their mean, and their spread gives the floor their noise adds to the relMSE")
      ->required();
  compare->add_option("--diff", cargs.diff, "Write a false-colour map of the relative error (with a colour bar)");
  compare->add_flag("--json", cargs.json, "Print the figures as one JSON object");

  ConvergeArgs vargs;
  SceneFlags converge_flags;
  CLI::App* converge = app.add_subcommand("converge", "Equal-time convergence of integrators against a reference");
  converge_flags.add(converge, vargs.common, false);
  converge->add_option("--reference", vargs.references,
                       "Reference image (.exr); given again, independent renders of the scene (other seeds), "
                       "compared against as their mean, whose noise floor is then reported and subtracted")
      ->required()
      ->allow_extra_args(false);
  converge->add_option("--integrators", vargs.integrators, "Integrators to compare, e.g. photon,path")
      ->delimiter(',')
      ->check(kIntegratorName)
      ->required();
  converge->add_option("--time", vargs.time, "Seconds per integrator (photon pass included)")
      ->required()
      ->check(kFinite & kPositive);
  converge->add_option("--checkpoints", vargs.checkpoints, "Seconds at which to record the error (default 1,2,4,...)")
      ->delimiter(',')
      ->check(kFinite & kPositive);
  converge->add_option("--out", vargs.out_dir, "Output folder (created if missing)")->required();

  PhotonsArgs pargs;
  SceneFlags photons_flags;
  CLI::App* photons = app.add_subcommand("photons", "Pictures and point clouds of the photon maps");
  photons_flags.add(photons, pargs.common, false);
  photons->add_option("--map", pargs.map,
                      "global, caustic, both (the surface maps), volume (in media: the volume maps) or all")
      ->check(CLI::IsMember({"global", "caustic", "both", "volume", "all"}));
  photons->add_option("-o,--output", pargs.output, "OUT.png (photons splatted through the camera) or OUT.ply")
      ->required();
  photons->add_flag("--heatmap", pargs.heatmap, "PNG: photon density as a false-colour heat map");

  PluginsArgs plugins_args;
  CLI::App* plugins = app.add_subcommand("plugins", "List the BSDFs, textures, lights, shapes and integrators this build knows");
  plugins->add_option("--dict", plugins_args.dict, "Print a libFuzzer dictionary for the json or xml scene reader instead")
      ->check(CLI::IsMember({"json", "xml"}));

  // CLI11 answers an unknown command with "A subcommand is required".
  if (argc > 1 && argv[1][0] != '-') {
    std::string known;
    bool found = false;
    for (const CLI::App* sub : app.get_subcommands({})) {
      known += (known.empty() ? "" : ", ") + sub->get_name();
      found = found || sub->get_name() == argv[1];
    }
    if (!found) {
      std::cerr << "error: unknown command \"" << argv[1] << "\" (known: " << known << "; see caustica --help)\n";
      return 1;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;
  }
  const Cluster& cluster = Cluster::world();
  if (cluster.distributed() && !render->parsed() && !converge->parsed()) {
    if (cluster.root()) std::cerr << "error: only `caustica render` and `converge` run on several MPI ranks\n";
    return 1;
  }
  // On several ranks an error ends the whole job (MPI_Abort): the other ranks would otherwise
  // wait for this one in the next collective call. Each message names its rank.
  auto fail = [&](const std::string& what, int code) {
    if (!cluster.distributed()) {
      std::cerr << what << "\n";
      return code;
    }
    std::cerr << what << " (" << cluster.describe_rank() << ")\n" << std::flush;
    cluster.abort(code);
  };
  try {
    if (render->parsed()) {
      render_flags.collect();
      if (!args.integrator.empty() && args.integrator[0] != ':') {
        args.common.mitsuba.integrator_replaced_by = "--integrator " + args.integrator;
      }
      return run_render(args);
    }
    if (compare->parsed()) return run_compare(cargs);
    if (converge->parsed()) {
      converge_flags.collect();
      // Every integrator named: the scene's own is not rendered.
      if (std::none_of(vargs.integrators.begin(), vargs.integrators.end(), [](const std::string& s) { return s.empty() || s[0] == ':'; })) {
        std::string names;
        for (const std::string& s : vargs.integrators) names += (names.empty() ? "" : ",") + s;
        vargs.common.mitsuba.integrator_replaced_by = "--integrators " + names;
      }
      return run_converge(vargs);
    }
    if (photons->parsed()) {
      photons_flags.collect();
      return run_photons(pargs);
    }
    if (plugins->parsed()) return run_plugins(plugins_args);
  } catch (const InputError& e) {
    return fail(std::string("error: ") + e.what(), 1);
  } catch (const std::bad_alloc&) {
    // What check_memory() did not foresee (it checks the large allocations before they are made).
    // Describing the limit allocates too: if that fails as well, the message says less.
    std::string message = "error: out of memory; try a smaller image, fewer photons or fewer threads";
    try {
      const MemoryLimit limit = memory_limit();
      if (!limit.what.empty()) {
        message = "error: out of memory (" + limit.what + " leaves " + format_gib(double(limit.bytes)) +
                  "); try a smaller image, fewer photons or fewer threads";
      }
    } catch (...) {
    }
    return fail(message, 1);
  } catch (const std::exception& e) {
    return fail(std::string("internal error: ") + e.what(), 2);
  }
  return 0;
}

}  // namespace caustica
