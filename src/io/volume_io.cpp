#include "io/file_bytes.h"
#include "io/volume_io.h"
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include "core/error.h"
#include "io/vdb_io.h"

namespace caustica {

namespace {
constexpr size_t kHeader = 4 + 4 * 5 + 4 * 6;  // "VOL" + version, 5 int32, 6 float32
constexpr uint64_t kMaxVoxels = uint64_t(1) << 30;  // 4 GiB of float32 a channel

template <class T>
T read_at(const std::string& b, size_t offset) {
  T v;
  std::memcpy(&v, b.data() + offset, sizeof(T));
  return v;
}
}  // namespace

VolumeGrid parse_vol(const std::string& b, const std::string& name, bool signed_values) {
  auto fail = [&](const std::string& m) -> void { throw InputError(name + ": " + m); };
  if (b.size() < 4 || b.compare(0, 3, "VOL") != 0) fail("not a .vol grid file (it does not start with \"VOL\")");
  if (uint8_t(b[3]) != 3) fail("version " + std::to_string(int(uint8_t(b[3]))) + " of the .vol format; version 3 is read");
  if (b.size() < kHeader) fail("truncated: " + std::to_string(b.size()) + " bytes, shorter than the 48-byte header");
  const int32_t encoding = read_at<int32_t>(b, 4);
  if (encoding != 1) fail("voxel encoding " + std::to_string(encoding) + "; only 1 (float32) is read");
  VolumeGrid g;
  g.nx = read_at<int32_t>(b, 8);
  g.ny = read_at<int32_t>(b, 12);
  g.nz = read_at<int32_t>(b, 16);
  g.channels = read_at<int32_t>(b, 20);
  if (g.nx < 1 || g.ny < 1 || g.nz < 1) {
    fail("the header gives " + std::to_string(g.nx) + " x " + std::to_string(g.ny) + " x " + std::to_string(g.nz) +
         " voxels; each must be at least 1");
  }
  if (g.channels != 1 && g.channels != 3) fail(std::to_string(g.channels) + " channels; 1 or 3 are read");
  const uint64_t voxels = uint64_t(g.nx) * uint64_t(g.ny) * uint64_t(g.nz);
  if (voxels > kMaxVoxels) fail(std::to_string(voxels) + " voxels, more than the 2^30 read");
  float box[6];
  for (int i = 0; i < 6; ++i) box[i] = read_at<float>(b, 24 + 4 * size_t(i));
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(box[a]) || !std::isfinite(box[a + 3]) || !(box[a] < box[a + 3]))
      fail("the bounding box is empty or not finite along axis " + std::to_string(a));
  }
  g.box.lo = Vec3(box[0], box[1], box[2]);
  g.box.hi = Vec3(box[3], box[4], box[5]);
  const uint64_t values = voxels * uint64_t(g.channels);
  const uint64_t expected = kHeader + 4 * values;
  if (uint64_t(b.size()) != expected) {
    fail("the header says " + std::to_string(g.nx) + " x " + std::to_string(g.ny) + " x " + std::to_string(g.nz) +
         " voxels of " + std::to_string(g.channels) + " channel(s), " + std::to_string(expected) +
         " bytes in all; the file has " + std::to_string(b.size()) + (b.size() < expected ? " (truncated)" : ""));
  }
  g.values.resize(size_t(values));
  std::memcpy(g.values.data(), b.data() + kHeader, size_t(values) * 4);
  for (size_t i = 0; i < g.values.size(); ++i) {
    const float v = g.values[i];
    if (!std::isfinite(v) || (v < 0.0f && !signed_values)) {
      const size_t voxel = i / size_t(g.channels);
      const size_t x = voxel % size_t(g.nx), y = voxel / size_t(g.nx) % size_t(g.ny), z = voxel / size_t(g.nx) / size_t(g.ny);
      std::ostringstream m;
      m << "voxel (" << x << ", " << y << ", " << z << ") holds " << v << "; values must be finite"
        << (signed_values ? "" : " and not negative");
      fail(m.str());
    }
  }
  return g;
}

VolumeGrid read_vol_file(const std::string& path, bool signed_values) {
  return parse_vol(read_file_bytes(path, "grid file"), path, signed_values);
}

VolumeGrid read_grid_file(const std::string& path, const std::string& grid_name) {
  char head[4] = {0, 0, 0, 0};
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open the grid file");
    in.read(head, 4);
  }
  // OpenVDB's magic number, 0x56444220 as a little-endian 64-bit integer: " BDV".
  if (std::memcmp(head, " BDV", 4) == 0) return read_vdb_file(path, grid_name);
  if (!grid_name.empty()) throw InputError(path + ": \"grid\" names a grid of an OpenVDB file; this is a .vol file");
  return read_vol_file(path);
}

std::string format_vol(const VolumeGrid& g) {
  std::string b = "VOL";
  b.push_back(char(3));
  auto put = [&](const void* p, size_t n) { b.append(static_cast<const char*>(p), n); };
  const int32_t head[5] = {1, g.nx, g.ny, g.nz, g.channels};
  put(head, sizeof(head));
  const float box[6] = {g.box.lo.x, g.box.lo.y, g.box.lo.z, g.box.hi.x, g.box.hi.y, g.box.hi.z};
  put(box, sizeof(box));
  put(g.values.data(), g.values.size() * sizeof(float));
  return b;
}

}  // namespace caustica
