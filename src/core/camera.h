// Pinhole camera: position, look-at, up, vertical field of view, resolution.
#pragma once
#include "core/math.h"

namespace caustica {

class Camera {
 public:
  Camera() = default;
  Camera(const Vec3& position, const Vec3& look_at, const Vec3& up, float vfov_degrees, int width, int height);
  // Ray through film position (x, y) in pixels, y down from the top.
  Ray generate_ray(float x, float y) const;
  // Projects a world point to film coordinates; false when behind the camera or off the film.
  bool project(const Vec3& p, float& x, float& y) const;
  int width() const { return width_; }
  int height() const { return height_; }
  const Vec3& position() const { return position_; }
  float vfov_degrees() const { return vfov_; }
  void set_resolution(int width, int height);

 private:
  Vec3 position_{0.0f}, forward_{0, 0, 1}, right_{1, 0, 0}, up_{0, 1, 0};
  float vfov_ = 45.0f, tan_half_ = 0.414f, aspect_ = 1.0f;
  int width_ = 1, height_ = 1;
};

}  // namespace caustica
