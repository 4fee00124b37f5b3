// Pinhole camera: position, look-at, up, field of view along a chosen axis, film and crop window;
// or an orthographic one (Mitsuba's `orthographic`): parallel rays from a rectangle of given size.
#pragma once
#include "core/math.h"

namespace caustica {

// Which extent of the film the field of view spans (Mitsuba's fov_axis).
enum class FovAxis { X, Y, Smaller, Larger, Diagonal };

class Camera {
 public:
  Camera() = default;
  Camera(const Vec3& position, const Vec3& look_at, const Vec3& up, float vfov_degrees, int width, int height);
  // Ray through image position (x, y) in pixels, y down from the top (crop window applied).
  Ray generate_ray(float x, float y) const;
  // Ray through image pixel (px, py) at offset `jitter` in [0, 1)^2: the same ray whether the
  // pixel is rendered in a crop window or on the whole film.
  Ray generate_ray(int px, int py, const Vec2& jitter) const;
  // With a thin lens: `lens` in [0, 1)^2 picks the point on the aperture.
  Ray generate_ray(int px, int py, const Vec2& jitter, const Vec2& lens) const;
  // A thin lens of this radius focused at this distance along the view direction (Mitsuba's
  // thinlens); radius 0 is the pinhole.
  void set_lens(float aperture_radius, float focus_distance);
  bool has_lens() const { return lens_radius_ > 0.0f; }
  // Parallel projection: rays along the view direction from a rectangle `view_width` by
  // `view_height` world units, centred on the position (0 height: the film's aspect).
  void set_orthographic(float view_width, float view_height);
  bool orthographic() const { return ortho_width_ > 0.0f; }
  // Where the camera sees world point p from: its position, or for an orthographic camera the
  // point on its image plane in front of p.
  Vec3 eye_for(const Vec3& p) const;
  // Projects a world point to image coordinates; false when behind the camera or off the image.
  bool project(const Vec3& p, float& x, float& y) const;
  // Image (crop window) size in pixels.
  int width() const { return width_; }
  int height() const { return height_; }
  const Vec3& position() const { return position_; }
  // The film and the crop window's corner on it.
  int film_width() const { return film_width_; }
  int film_height() const { return film_height_; }
  int crop_x() const { return crop_x_; }
  int crop_y() const { return crop_y_; }
  float vfov_degrees() const;
  // The whole film; clears a crop window.
  void set_resolution(int width, int height);
  // Renders only the window [x, x + width) x [y, y + height) of the film.
  void set_crop(int x, int y, int width, int height);
  // `degrees` spans the film along `axis`; recomputed for the film's aspect on set_resolution.
  void set_fov(float degrees, FovAxis axis);
  // Mirrors the image left-right (a camera transform with a negative determinant).
  void set_mirror(bool mirror);

 private:
  void update_tan();
  // Half the orthographic view's height: given, or from the width and the film's aspect.
  float ortho_half_height() const { return 0.5f * (ortho_height_ > 0.0f ? ortho_height_ : ortho_width_ / aspect_); }
  // The ray through position (fx, fy) of the whole film, in pixels.
  Ray film_ray(float fx, float fy) const;
  Vec3 position_{0.0f}, forward_{0, 0, 1}, right_{1, 0, 0}, up_{0, 1, 0};
  float fov_ = 45.0f, tan_half_ = 0.414f, aspect_ = 1.0f;
  FovAxis axis_ = FovAxis::Y;
  bool mirror_ = false;
  float lens_radius_ = 0.0f, focus_distance_ = 1.0f;
  int film_width_ = 1, film_height_ = 1, crop_x_ = 0, crop_y_ = 0;
  int width_ = 1, height_ = 1;
  float ortho_width_ = 0.0f, ortho_height_ = 0.0f;  // world units; 0: perspective
};

}  // namespace caustica
