// Volumes: values over space that media read (Mitsuba's `volume` plugins): a constant, or a
// grid of voxels from a file (Mitsuba's binary .vol, or an OpenVDB .vdb), interpolated within
// a box placed in the scene by a transform.
#pragma once
#include <memory>
#include <vector>
#include "core/math.h"
#include "core/params.h"
#include "core/shape.h"

namespace caustica {

// A voxel grid as a .vol file holds it: x fastest, then y, then z, `channels` values a voxel
// (1 or 3). Its samples span `box` corner to corner (Mitsuba 0.6's convention): voxel (i, j, k)
// sits at lo + (i / (nx - 1), j / (ny - 1), k / (nz - 1)) * extent, and `to_world` places the
// box in the scene (a .vdb's index-to-world map; identity for a .vol).
struct VolumeGrid {
  int nx = 0, ny = 0, nz = 0, channels = 1;
  Bounds box;
  glm::mat4 to_world{1.0f};
  std::vector<float> values;
};

class Volume {
 public:
  virtual ~Volume() = default;
  virtual Color eval(const Vec3& p) const = 0;
  // An upper bound of every channel's value anywhere (delta tracking's majorant).
  virtual float max_value() const = 0;
  // 1 where every channel holds the same value.
  virtual int channels() const = 0;
  // Where the volume may be non-zero; empty() for all of space.
  virtual Bounds bounds() const = 0;
};

// The world-space box around the unit cube under an affine transform.
Bounds unit_cube_bounds(const glm::mat4& to_world);

class ConstVolume final : public Volume {
 public:
  // `bounds` empty: everywhere (Mitsuba's constvolume inside a heterogeneous medium is bounded
  // by the unit cube under its to_world instead).
  explicit ConstVolume(const Color& value, const Bounds& bounds = Bounds{}) : value_(value), bounds_(bounds) {}
  Color eval(const Vec3&) const override { return value_; }
  float max_value() const override { return max_component(value_); }
  int channels() const override { return value_.x == value_.y && value_.y == value_.z ? 1 : 3; }
  Bounds bounds() const override { return bounds_; }
  static std::unique_ptr<Volume> create(const Params& p);

 private:
  Color value_;
  Bounds bounds_;
};

// How a grid's voxels map onto space.
struct GridPlacement {
  glm::mat4 to_world{1.0f};  // applied after the grid's own box and transform
  // The box the voxels fill: the file's (false), or the unit cube (Mitsuba 3's default, which
  // ignores the file's box).
  bool unit_box = false;
  // Voxel values sit at the cells' centres, values beyond the outer centres held to the box's
  // faces and coordinates outside the box clamped to it (Mitsuba 3's grids); else at the box's
  // corners, zero outside it (Mitsuba 0.6's).
  bool cell_centres = false;
  bool nearest = false;  // nearest voxel, not trilinear
};

class GridVolume final : public Volume {
 public:
  explicit GridVolume(VolumeGrid grid, const GridPlacement& placement = GridPlacement{});
  Color eval(const Vec3& p) const override;
  float max_value() const override { return max_; }
  int channels() const override { return grid_.channels; }
  Bounds bounds() const override { return bounds_; }
  static std::unique_ptr<Volume> create(const Params& p);

 private:
  VolumeGrid grid_;
  GridPlacement placement_;
  glm::mat4 to_grid_;  // world to the box's [0, 1]^3
  Bounds bounds_;
  float max_ = 0;
  Color voxel(int x, int y, int z) const;
};

}  // namespace caustica
