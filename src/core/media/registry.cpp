// The medium and phase-function families' tables: one row a plugin.
#include "core/media/registry.h"
#include "core/media/heterogeneous.h"
#include "core/media/homogeneous.h"

namespace caustica {

const std::vector<MediumPlugin>& medium_plugins() {
  static const std::vector<MediumPlugin> table = {
      {"homogeneous", true, HomogeneousMedium::create, {"sigma_t", "albedo", "sigma_a", "sigma_s", "scale", "phase"}},
      {"heterogeneous", true, HeterogeneousMedium::create, {"sigma_t", "albedo", "scale", "phase"}},
  };
  return table;
}

const std::vector<PhasePlugin>& phase_plugins() {
  static const std::vector<PhasePlugin> table = {
      {"isotropic", true, IsotropicPhase::create, {}},
      {"hg", true, HenyeyGreenstein::create, {"g"}},
  };
  return table;
}

const std::vector<VolumePlugin>& volume_plugins() {
  static const std::vector<VolumePlugin> table = {
      {"constvolume", true, ConstVolume::create, {"value", "to_world"}},
      {"gridvolume", true, GridVolume::create, {"filename", "grid", "to_world", "box", "voxels", "filter"}},
  };
  return table;
}

}  // namespace caustica
