// Pinhole camera.
#include "core/camera.h"
#include "core/sampling.h"

namespace caustica {

Camera::Camera(const Vec3& position, const Vec3& look_at, const Vec3& up, float vfov_degrees, int width, int height)
    : position_(position), fov_(vfov_degrees) {
  forward_ = glm::normalize(look_at - position);
  right_ = glm::normalize(glm::cross(forward_, up));
  up_ = glm::cross(right_, forward_);
  set_resolution(width, height);
}

void Camera::set_resolution(int width, int height) {
  film_width_ = width_ = width;
  film_height_ = height_ = height;
  crop_x_ = crop_y_ = 0;
  aspect_ = static_cast<float>(width) / static_cast<float>(height);
  update_tan();
}

void Camera::set_crop(int x, int y, int width, int height) {
  crop_x_ = x;
  crop_y_ = y;
  width_ = width;
  height_ = height;
}

void Camera::set_fov(float degrees, FovAxis axis) {
  fov_ = degrees;
  axis_ = axis;
  update_tan();
}

void Camera::set_lens(float aperture_radius, float focus_distance) {
  lens_radius_ = aperture_radius;
  focus_distance_ = focus_distance;
}

Ray Camera::generate_ray(int px, int py, const Vec2& jitter, const Vec2& lens) const {
  Ray ray = generate_ray(px, py, jitter);
  if (lens_radius_ <= 0.0f) return ray;
  // The pinhole ray meets the plane of focus; the lens ray starts on the aperture and aims there.
  const Vec3 focus = ray.origin + ray.dir * (focus_distance_ / glm::dot(ray.dir, forward_));
  const Vec2 d = lens_radius_ * sample_concentric_disk(lens);
  ray.origin = position_ + d.x * right_ + d.y * up_;
  ray.dir = glm::normalize(focus - ray.origin);
  return ray;
}

void Camera::set_orthographic(float view_width, float view_height) {
  ortho_width_ = view_width;
  ortho_height_ = view_height;
}

Vec3 Camera::eye_for(const Vec3& p) const {
  if (!orthographic()) return position_;
  return p - glm::dot(p - position_, forward_) * forward_;
}

void Camera::set_mirror(bool mirror) {
  if (mirror != mirror_) right_ = -right_;
  mirror_ = mirror;
}

// tan_half_ is the tangent of half the vertical angle.
void Camera::update_tan() {
  const float t = std::tan(0.5f * fov_ * kPi / 180.0f);
  const float w = float(film_width_), h = float(film_height_);
  switch (axis_) {
    case FovAxis::Y: tan_half_ = t; break;
    case FovAxis::X: tan_half_ = t * h / w; break;
    case FovAxis::Smaller: tan_half_ = w < h ? t * h / w : t; break;
    case FovAxis::Larger: tan_half_ = w > h ? t * h / w : t; break;
    case FovAxis::Diagonal: tan_half_ = t * h / std::sqrt(w * w + h * h); break;
  }
}

float Camera::vfov_degrees() const { return 2.0f * std::atan(tan_half_) * 180.0f / kPi; }

// The film position (fx, fy) in pixels of the whole film as (sx, sy) in [-1, 1]^2, x right, y up.
static Vec2 film_to_screen(float fx, float fy, int film_w, int film_h) {
  return Vec2(2.0f * fx / float(film_w) - 1.0f, 1.0f - 2.0f * fy / float(film_h));
}

Ray Camera::film_ray(float fx, float fy) const {
  const Vec2 s = film_to_screen(fx, fy, film_width_, film_height_);
  if (orthographic()) {
    return Ray{position_ + (0.5f * ortho_width_ * s.x) * right_ + (ortho_half_height() * s.y) * up_, forward_, kInfinity};
  }
  return Ray{position_, glm::normalize(forward_ + (s.x * tan_half_ * aspect_) * right_ + (s.y * tan_half_) * up_), kInfinity};
}

Ray Camera::generate_ray(float x, float y) const { return film_ray(x + float(crop_x_), y + float(crop_y_)); }

Ray Camera::generate_ray(int px, int py, const Vec2& jitter) const {
  return film_ray(float(px + crop_x_) + jitter.x, float(py + crop_y_) + jitter.y);
}

bool Camera::project(const Vec3& p, float& x, float& y) const {
  const Vec3 d = p - position_;
  const float z = glm::dot(d, forward_);
  if (z <= 0.0f) return false;
  float sx, sy;
  if (orthographic()) {
    sx = glm::dot(d, right_) / (0.5f * ortho_width_);
    sy = glm::dot(d, up_) / ortho_half_height();
  } else {
    sx = glm::dot(d, right_) / (z * tan_half_ * aspect_);
    sy = glm::dot(d, up_) / (z * tan_half_);
  }
  x = 0.5f * (sx + 1.0f) * float(film_width_) - float(crop_x_);
  y = 0.5f * (1.0f - sy) * float(film_height_) - float(crop_y_);
  return x >= 0 && y >= 0 && x < float(width_) && y < float(height_);
}

}  // namespace caustica
