// Normal mapping.
#include "core/bsdf/normalmap.h"

namespace caustica {

Frame NormalMap::frame(const ShadingPoint& sp) const {
  const Vec3 n = 2.0f * Vec3(normals_.at(sp)) - Vec3(1.0f);
  const float len = glm::length(n);
  if (!(len > 1e-6f) || !std::isfinite(len)) return Frame();
  Frame f;
  f.n = n / len;
  const Vec3 s = Vec3(1.0f, 0.0f, 0.0f) - f.n * f.n.x;  // dp/du is the local s axis
  const float ls = glm::length(s);
  if (!(ls > 1e-6f)) return Frame(f.n);
  f.s = s / ls;
  f.t = glm::cross(f.n, f.s);
  return f;
}

std::unique_ptr<Bsdf> NormalMap::create(const Params& p) {
  const ColorParam normals = p.texture("normalmap", Color(0.5f, 0.5f, 1.0f));
  if (normals.texture && normals.texture->channels() != 3) {
    p.fail("normalmap", "a normal map needs three channels (x, y, z as r, g, b); this texture has " +
                            std::to_string(normals.texture->channels()));
  }
  if (!normals.texture && !(glm::length(2.0f * Vec3(normals.value) - Vec3(1.0f)) > 1e-6f)) {
    p.fail("normalmap", "the normal 2 rgb - 1 is zero");
  }
  const std::vector<const Bsdf*> nested = p.bsdfs("bsdf", false);
  return std::make_unique<NormalMap>(nested.front(), normals);
}

}  // namespace caustica
