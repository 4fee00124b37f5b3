// The medium family's table and the phase-function family's (a medium's nested `phase`): name,
// whether Mitsuba knows it by that name, create, keys. As the other families' tables, they
// feed the scene readers, error messages, the Mitsuba translator and `caustica plugins`.
#pragma once
#include <memory>
#include <vector>
#include "core/media/medium.h"
#include "core/media/phase.h"
#include "core/media/volume.h"
#include "core/params.h"

namespace caustica {

struct MediumPlugin {
  const char* name;
  bool mitsuba;
  std::unique_ptr<Medium> (*create)(const Params&);
  std::vector<const char*> keys;  // every key besides "type"
};
const std::vector<MediumPlugin>& medium_plugins();

struct PhasePlugin {
  const char* name;
  bool mitsuba;
  std::unique_ptr<PhaseFunction> (*create)(const Params&);
  std::vector<const char*> keys;
};
const std::vector<PhasePlugin>& phase_plugins();

// Volumes a medium reads its coefficients from (a medium's sigma_t and albedo blocks).
struct VolumePlugin {
  const char* name;
  bool mitsuba;
  std::unique_ptr<Volume> (*create)(const Params&);
  std::vector<const char*> keys;
};
const std::vector<VolumePlugin>& volume_plugins();

}  // namespace caustica
