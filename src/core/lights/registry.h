// The light (emitter) family's one table: name, whether Mitsuba knows it by that name, create,
// keys. Area lights have no row: the scene reader makes them from emissive objects (Mitsuba's
// `area` emitter nested in a shape).
#pragma once
#include <memory>
#include <string>
#include <vector>
#include "core/lights/light.h"
#include "core/params.h"
#include "core/registry.h"

namespace caustica {

using LightPlugin = FamilyRow<Light>;  // (keys: besides "type", "name" and "sampling_weight")

const std::vector<LightPlugin>& light_plugins();

}  // namespace caustica
