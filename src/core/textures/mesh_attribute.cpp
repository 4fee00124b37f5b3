// Mitsuba's `mesh_attribute`.
#include "core/textures/mesh_attribute.h"
#include "core/shape.h"

namespace caustica {

std::unique_ptr<Texture> MeshAttributeTexture::create(const Params& p) {
  const std::string name = p.string("name", "");
  if (name.rfind("vertex_", 0) != 0 && name.rfind("face_", 0) != 0) {
    p.fail("name", name.empty() ? "missing key \"name\" (the attribute: vertex_color, face_color, ...)"
                                : "the attribute's name must start with \"vertex_\" or \"face_\", not \"" + name + "\"");
  }
  return std::make_unique<MeshAttributeTexture>(name, float(p.number_in("scale", 1.0, 0.0, kMaxColor)));
}

Color MeshAttributeTexture::eval(const TexturePoint& p) const {
  if (!p.mesh) return Color(0.0f);
  const MeshAttribute* a = p.mesh->find(name_);
  return a ? a->at(p.triangle, p.bary) * scale_ : Color(0.0f);
}

}  // namespace caustica
