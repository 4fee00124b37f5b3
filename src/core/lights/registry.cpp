// The light family's table: one row a plugin.
#include "core/lights/registry.h"
#include "core/lights/directional.h"
#include "core/lights/environment.h"
#include "core/lights/point.h"
#include "core/lights/projector.h"
#include "core/lights/spot.h"

namespace caustica {

const std::vector<LightPlugin>& light_plugins() {
  static const std::vector<LightPlugin> table = {
      {"point", true, PointLight::create, {"position", "intensity"}},
      {"spot", true, create_spot_light,
       {"position", "direction", "target", "up", "intensity", "cutoff_angle", "beam_width", "texture"}},
      {"projector", true, create_projector_light,
       {"position", "direction", "target", "up", "irradiance", "scale", "fov", "fov_axis"}},
      {"directional", true, DirectionalLight::create, {"direction", "irradiance"}},
      {"constant", true, EnvironmentLight::create_constant, {"radiance"}},
      {"envmap", true, EnvironmentLight::create, {"filename", "scale", "to_world"}},
  };
  return table;
}

}  // namespace caustica
