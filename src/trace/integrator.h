// The integrator interface, the settings every Monte Carlo integrator shares, and the family's
// registry table: each integrator by name with the settings keys it reads. The command line's
// per-integrator flags and their "applies to" rules come from that table.
#pragma once
#include <algorithm>
#include <atomic>
#include <memory>
#include <string>
#include <vector>
#include "core/image.h"
#include "core/params.h"
#include "core/sampler.h"
#include "core/scene.h"
#include "io/json_reader.h"
#include "photon/photon_map.h"

namespace caustica {

struct PreprocessContext {
  uint64_t seed = 0;
  bool quiet = false;
  const std::atomic<bool>* cancel = nullptr;  // set (e.g. by SIGINT) to stop early
  int first_pass = 0;  // a progressive integrator's first pass here (an MPI rank's: its rank)
  // What the render will take, when known: its passes (samples per pixel) or, with a time
  // budget, seconds, over `ranks` processes. An integrator may weigh its choices by it (the
  // photon mapper's pilot: the bias of its progressive radii falls with the passes).
  int passes = 0;
  double time_budget = 0;
  int ranks = 1;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  // Work done once before the eye pass (the photon pass goes here).
  virtual void preprocess(const Scene&, const PreprocessContext&) {}
  // Progressive integrators change between passes (fresh photon maps, smaller radii): the
  // render loop then runs pass by pass and calls begin_pass(scene, i, context) before pass i.
  virtual bool progressive() const { return false; }
  // Prepares pass `pass` (0, 1, ...); false when cancelled, and the pass is not rendered.
  virtual bool begin_pass(const Scene&, int /*pass*/, const PreprocessContext&) { return true; }
  // Turns the per-pixel mean of Li over the passes into the image (SPPM adds its photon
  // statistics here); pixel_passes[i] is the number of passes pixel i received.
  virtual void resolve(Image& /*mean*/, const std::vector<int>& /*pixel_passes*/) const {}
  // Whether pass i depends on nothing but i, so that MPI ranks may render passes apart. SPPM's
  // per-pixel radii carry over from pass to pass, so its passes run in order on one process.
  virtual bool passes_independent() const { return true; }
  // Radiance arriving at the camera along `ray`.
  virtual Color Li(const Ray& ray, const Scene& scene, Sampler& sampler) const = 0;
  virtual std::string name() const = 0;
  // Settings and preprocess statistics, one "key: value" per line, for the render report.
  virtual std::string describe() const = 0;

  // Capabilities, asked instead of testing names or types.
  // Whether Li() fills the sampler's AOVs (photon count and gather radius: --aov).
  virtual bool supports_aov() const { return false; }
  // The photon maps after preprocess, for pictures of them; null where there are none.
  virtual const PhotonMap* global_map() const { return nullptr; }
  virtual const PhotonMap* caustic_map() const { return nullptr; }
  // In participating media: the maps of photons scattered in them (none elsewhere).
  virtual std::vector<const PhotonMap*> volume_maps() const { return {}; }
};

// What Monte Carlo integrators share (Mitsuba's MonteCarloIntegrator), read once by
// read_monte_carlo; each integrator's settings struct extends it.
struct MonteCarloSettings {
  int max_depth = 16;          // from the render block (and --max-depth)
  int rr_depth = 3;            // Russian roulette starts after this many bounces
  bool hide_emitters = false;  // directly visible emitters (and the environment) render black
};
MonteCarloSettings read_monte_carlo(const Params& p, const RenderSettings& render);

// One row of the integrator table: its name, its create function and the settings keys it
// reads (the block may hold no others).
struct IntegratorPlugin {
  const char* name;
  std::unique_ptr<Integrator> (*create)(const Params&, const RenderSettings&);
  std::vector<const char*> keys;
  // Whether the row lists `key`.
  bool reads(const std::string& key) const { return std::find(keys.begin(), keys.end(), key) != keys.end(); }
};
const std::vector<IntegratorPlugin>& integrator_plugins();
const IntegratorPlugin* find_integrator_plugin(const std::string& name);

// Every settings key that some integrator reads, once, with its kind and what it does: the
// command line offers each as a flag (--photons for "photons"; a boolean also as --no-...).
enum class SettingKind { Integer, Real, Boolean };
struct IntegratorSetting {
  const char* key;
  SettingKind kind;
  const char* help;
};
const std::vector<IntegratorSetting>& integrator_settings();
const IntegratorSetting* find_integrator_setting(const std::string& key);
// A setting's command-line flag: "--caustic-photons" for "caustic_photons".
std::string integrator_flag(const std::string& key);
// The names of the integrators whose row lists `key`, e.g. "photon, photon-direct".
std::string integrators_reading(const std::string& key);

// Prints (unless quiet) the warnings of `fresh` whose subject (the text before the colon) is not
// in `seen`, and records their subjects: a progressive integrator's passes repeat the photon
// pass's warnings, each with its own numbers.
void report_new_warnings(const std::vector<std::string>& fresh, std::vector<std::string>& seen, bool quiet);

// Creates the integrator `type`, reading its settings (unknown keys are errors).
// Throws InputError listing the valid names when `type` is unknown.
std::unique_ptr<Integrator> create_integrator(const std::string& type, const JsonSource& settings,
                                              const RenderSettings& render);
// The integrators by name, comma-separated, for messages and help.
std::string known_integrators();
// "unknown integrator \"NAME\" (known: ...)": the one message for a name no row has.
std::string unknown_integrator(const std::string& name);

}  // namespace caustica
