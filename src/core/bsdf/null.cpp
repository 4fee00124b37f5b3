// Mitsuba's `null`.
#include "core/bsdf/null.h"

namespace caustica {

std::unique_ptr<Bsdf> NullBsdf::create(const Params&) { return std::make_unique<NullBsdf>(); }

}  // namespace caustica
