// Volumes: values over space that media read (Mitsuba's `volume` plugins): a constant, or a
// grid of voxels from a file (Mitsuba's binary .vol), trilinearly interpolated within the box
// the file gives and zero outside it.
#pragma once
#include <memory>
#include <vector>
#include "core/math.h"
#include "core/params.h"
#include "core/shape.h"

namespace caustica {

// A voxel grid as a .vol file holds it: x fastest, then y, then z, `channels` values a voxel
// (1 or 3). Its samples span `box` corner to corner (Mitsuba's convention): voxel (i, j, k)
// sits at lo + (i / (nx - 1), j / (ny - 1), k / (nz - 1)) * extent.
struct VolumeGrid {
  int nx = 0, ny = 0, nz = 0, channels = 1;
  Bounds box;
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
  // Where the volume may be non-zero; empty() for all of space (a constant).
  virtual Bounds bounds() const = 0;
};

class ConstVolume final : public Volume {
 public:
  explicit ConstVolume(const Color& value) : value_(value) {}
  Color eval(const Vec3&) const override { return value_; }
  float max_value() const override { return max_component(value_); }
  int channels() const override { return value_.x == value_.y && value_.y == value_.z ? 1 : 3; }
  Bounds bounds() const override { return Bounds{}; }
  static std::unique_ptr<Volume> create(const Params& p);

 private:
  Color value_;
};

class GridVolume final : public Volume {
 public:
  explicit GridVolume(VolumeGrid grid);
  Color eval(const Vec3& p) const override;
  float max_value() const override { return max_; }
  int channels() const override { return grid_.channels; }
  Bounds bounds() const override { return grid_.box; }
  static std::unique_ptr<Volume> create(const Params& p);

 private:
  VolumeGrid grid_;
  float max_ = 0;
  Color voxel(int x, int y, int z) const;
};

}  // namespace caustica
