// Pinhole camera.
#include "core/camera.h"

namespace caustica {

Camera::Camera(const Vec3& position, const Vec3& look_at, const Vec3& up, float vfov_degrees, int width, int height)
    : position_(position), vfov_(vfov_degrees) {
  forward_ = glm::normalize(look_at - position);
  right_ = glm::normalize(glm::cross(forward_, up));
  up_ = glm::cross(right_, forward_);
  tan_half_ = std::tan(0.5f * vfov_degrees * kPi / 180.0f);
  set_resolution(width, height);
}

void Camera::set_resolution(int width, int height) {
  width_ = width;
  height_ = height;
  aspect_ = static_cast<float>(width) / static_cast<float>(height);
}

Ray Camera::generate_ray(float x, float y) const {
  const float sx = (2.0f * x / width_ - 1.0f) * tan_half_ * aspect_;
  const float sy = (1.0f - 2.0f * y / height_) * tan_half_;
  return Ray{position_, glm::normalize(forward_ + sx * right_ + sy * up_), kInfinity};
}

bool Camera::project(const Vec3& p, float& x, float& y) const {
  const Vec3 d = p - position_;
  const float z = glm::dot(d, forward_);
  if (z <= 0.0f) return false;
  const float sx = glm::dot(d, right_) / (z * tan_half_ * aspect_);
  const float sy = glm::dot(d, up_) / (z * tan_half_);
  x = 0.5f * (sx + 1.0f) * width_;
  y = 0.5f * (1.0f - sy) * height_;
  return x >= 0 && y >= 0 && x < width_ && y < height_;
}

}  // namespace caustica
