// Named indices of refraction, as Mitsuba 3 names them: dielectrics ("bk7", "water", ...) and
// conductors ("Au", "Cu", ... every table Mitsuba has) with RGB values.
#pragma once
#include <string>
#include "core/bsdf/conductor.h"

namespace caustica {

// False when the name is unknown; known_dielectrics() lists the names for messages.
bool lookup_dielectric_ior(const std::string& name, float& ior);
std::string known_dielectrics();
bool lookup_conductor(const std::string& name, ConductorIor& ior);
std::string known_conductors();

}  // namespace caustica
