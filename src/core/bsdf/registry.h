// The BSDF family's one table: every plugin's name, whether Mitsuba knows it by that name, its
// create function and the keys it reads. Scene readers, error messages, the Mitsuba
// translator, `caustica plugins` and the documentation tests all take the family from here.
#pragma once
#include <memory>
#include <string>
#include <vector>
#include "core/bsdf/bsdf.h"
#include "core/params.h"

namespace caustica {

struct BsdfPlugin {
  const char* name;
  bool mitsuba;   // Mitsuba 3 has a plugin of this name and parameters (else it is our alias)
  bool can_emit;  // the block may carry an "emission" (its area light's radiance)
  std::unique_ptr<Bsdf> (*create)(const Params&);
  std::vector<const char*> keys;  // every key besides "type" (and "emission")
};

const std::vector<BsdfPlugin>& bsdf_plugins();
// nullptr for a name not in the table.
const BsdfPlugin* find_bsdf_plugin(const std::string& name);
// "diffuse, conductor, ...", for messages.
std::string known_bsdfs();

}  // namespace caustica
