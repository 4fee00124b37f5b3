// The factory table: every integrator by name (Tungsten's IntegratorFactory in spirit).
#include "trace/integrator.h"
#include <algorithm>
#include <functional>
#include <iostream>
#include "trace/path.h"
#include "trace/photon_integrator.h"
#include "trace/sppm.h"
#include "trace/whitted.h"

namespace caustica {
namespace {

using Maker = std::function<std::unique_ptr<Integrator>(const JsonSource&, const RenderSettings&)>;

const std::vector<std::pair<std::string, Maker>>& table() {
  static const std::vector<std::pair<std::string, Maker>> t = {
      {"path", [](const JsonSource& s, const RenderSettings& r) { return std::make_unique<PathIntegrator>(s, r); }},
      {"photon", [](const JsonSource& s, const RenderSettings& r) { return std::make_unique<PhotonIntegrator>(s, r, true); }},
      {"photon-direct", [](const JsonSource& s, const RenderSettings& r) { return std::make_unique<PhotonIntegrator>(s, r, false); }},
      {"sppm", [](const JsonSource& s, const RenderSettings& r) { return std::make_unique<SppmIntegrator>(s, r); }},
      {"whitted", [](const JsonSource& s, const RenderSettings& r) { return std::make_unique<WhittedIntegrator>(s, r); }},
  };
  return t;
}

}  // namespace

void report_new_warnings(const std::vector<std::string>& fresh, std::vector<std::string>& seen, bool quiet) {
  for (const std::string& w : fresh) {
    if (std::find(seen.begin(), seen.end(), w) != seen.end()) continue;
    if (!quiet) std::cerr << "warning: " << w << "\n";
    seen.push_back(w);
  }
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const auto& e : table()) names.push_back(e.first);
  return names;
}

std::unique_ptr<Integrator> create_integrator(const std::string& type, const JsonSource& settings,
                                              const RenderSettings& render) {
  for (const auto& e : table()) {
    if (e.first == type) return e.second(settings, render);
  }
  std::string known;
  for (const auto& n : integrator_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("unknown integrator \"" + type + "\" (known: " + known + ")");
}

}  // namespace caustica
