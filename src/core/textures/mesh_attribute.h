// Mitsuba's `mesh_attribute`: a value the hit mesh carries per vertex (interpolated by the
// point's barycentrics) or per face, times `scale`. `name` is Mitsuba's: "vertex_color",
// "face_color", or "vertex_" / "face_" followed by a PLY property's prefix. On a surface
// without the attribute the texture is black; a scene in which no mesh carries it is an error
// at load (io/scene_loader.cpp).
#pragma once
#include <memory>
#include <string>
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

class MeshAttributeTexture final : public Texture {
 public:
  MeshAttributeTexture(std::string name, float scale) : name_(std::move(name)), scale_(scale) {}
  static std::unique_ptr<Texture> create(const Params& p);
  Color eval(const TexturePoint& p) const override;
  const std::string& name() const { return name_; }
  float scale() const { return scale_; }

 private:
  std::string name_;
  float scale_;
};

}  // namespace caustica
