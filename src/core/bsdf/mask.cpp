// Mitsuba's `mask`.
#include "core/bsdf/mask.h"

namespace caustica {

std::unique_ptr<Bsdf> Mask::create(const Params& p) {
  const Bsdf* nested = p.bsdfs("bsdf", false).front();
  const ColorParam opacity = p.texture("opacity", Color(0.5f));
  if (!opacity.texture && max_component(opacity.value) > 1.0f) p.fail("opacity", "opacity must lie in [0, 1]");
  return std::make_unique<Mask>(nested, opacity);
}

}  // namespace caustica
