// The light (emitter) family's one table: name, whether Mitsuba knows it by that name, create,
// keys. Area lights have no row: the scene reader makes them from emissive objects (Mitsuba's
// `area` emitter nested in a shape).
#pragma once
#include <memory>
#include <string>
#include <vector>
#include "core/lights/light.h"
#include "core/params.h"

namespace caustica {

struct LightPlugin {
  const char* name;
  bool mitsuba;
  std::unique_ptr<Light> (*create)(const Params&);
  std::vector<const char*> keys;  // every key besides "type" (and "name")
};

const std::vector<LightPlugin>& light_plugins();

}  // namespace caustica
