// The medium family's table, the phase-function family's (a medium's nested `phase`) and the
// volume family's (its coefficients): FamilyRow's. As the other families' tables, they feed the
// scene readers, error messages, the Mitsuba translator and `caustica plugins`.
#pragma once
#include <memory>
#include <vector>
#include "core/media/medium.h"
#include "core/media/phase.h"
#include "core/media/volume.h"
#include "core/params.h"
#include "core/registry.h"

namespace caustica {

using MediumPlugin = FamilyRow<Medium>;
const std::vector<MediumPlugin>& medium_plugins();

using PhasePlugin = FamilyRow<PhaseFunction>;
const std::vector<PhasePlugin>& phase_plugins();

// Volumes a medium reads its coefficients from (a medium's sigma_t and albedo blocks).
using VolumePlugin = FamilyRow<Volume>;
const std::vector<VolumePlugin>& volume_plugins();

}  // namespace caustica
