#include "io/file_bytes.h"
#include "io/vdb_io.h"
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <sstream>
#include "core/error.h"

#ifdef CAUSTICA_OPENVDB
#include <openvdb/openvdb.h>
#endif

namespace caustica {

namespace {
constexpr uint64_t kMaxVoxels = uint64_t(1) << 30;
}

void check_vdb_structure(const std::string& b, const std::string& name) {
  auto fail = [&](const std::string& m) -> void { throw InputError(name + ": " + m); };
  size_t at = 0;
  auto need = [&](size_t n, const char* what) {
    if (n > b.size() - at) fail(std::string("truncated in ") + what + " (byte " + std::to_string(at) + " of " + std::to_string(b.size()) + ")");
  };
  // Reads one little-endian value of zero's type.
  auto value = [&](auto zero, const char* what) {
    need(sizeof zero, what);
    std::memcpy(&zero, b.data() + at, sizeof zero);
    at += sizeof zero;
    return zero;
  };
  auto u32 = [&](const char* what) { return value(uint32_t(0), what); };
  auto i64 = [&](const char* what) { return value(int64_t(0), what); };
  auto skip = [&](size_t n, const char* what) {
    need(n, what);
    at += n;
  };
  auto text = [&](const char* what) {
    const uint32_t n = u32(what);
    need(n, what);
    const std::string s = b.substr(at, n);
    at += n;
    return s;
  };
  if (b.size() < 8 || std::memcmp(b.data(), " BDV\0\0\0\0", 8) != 0) fail("not an OpenVDB file (no \"VDB\" magic number)");
  at = 8;
  const uint32_t version = u32("the header");
  if (version < 220 || version > 224) {
    fail("OpenVDB file format version " + std::to_string(version) + "; versions 220 to 224 (OpenVDB 3 to 10) are read");
  }
  skip(8, "the header");  // the library's version
  need(1, "the header");
  const bool offsets = b[at++] != 0;
  if (!offsets) fail("written as a stream (without grid offsets); write it as a file");
  if (version < 222) skip(1, "the header");  // a compression flag
  skip(36, "the header");                   // the UUID
  // The file's metadata: a count, then name, type name and value, each length-prefixed.
  const uint32_t entries = u32("the file's metadata");
  if (entries > 100000) fail(std::to_string(entries) + " metadata entries: a corrupt header");
  for (uint32_t i = 0; i < entries; ++i) {
    text("the file's metadata");
    text("the file's metadata");
    text("the file's metadata");
  }
  const uint32_t grids = u32("the grid count");
  if (grids == 0 || grids > 100000) fail(std::to_string(grids) + " grids: a corrupt header");
  for (uint32_t i = 0; i < grids; ++i) {
    const size_t descriptor = at;
    text("a grid descriptor");                     // its unique name
    text("a grid descriptor");                     // its type
    text("a grid descriptor");                     // the grid it instances
    const int64_t grid_pos = i64("a grid descriptor"), block_pos = i64("a grid descriptor"), end_pos = i64("a grid descriptor");
    if (!(grid_pos >= int64_t(at) && grid_pos <= block_pos && block_pos <= end_pos)) {
      fail("grid " + std::to_string(i) + "'s descriptor (byte " + std::to_string(descriptor) + ") gives its data out of order");
    }
    if (uint64_t(end_pos) > uint64_t(b.size())) {
      fail("truncated: grid " + std::to_string(i) + " ends at byte " + std::to_string(end_pos) + ", the file has " +
           std::to_string(b.size()));
    }
    // The grid's own metadata, within its data: its compression flags, then name, type and
    // value of each entry. OpenVDB's delayed-loading entry starts with a count it allocates
    // for (one per leaf node): at most one per byte of the grid.
    const size_t next = at;
    at = size_t(grid_pos);
    u32("a grid's compression flags");
    const uint32_t grid_entries = u32("a grid's metadata");
    if (grid_entries > 100000) fail("grid " + std::to_string(i) + ": " + std::to_string(grid_entries) + " metadata entries: corrupt");
    for (uint32_t e = 0; e < grid_entries; ++e) {
      text("a grid's metadata");
      const std::string type = text("a grid's metadata");
      const uint32_t n = u32("a grid's metadata");
      need(n, "a grid's metadata");
      if (type == "__delayedload" && n >= 4) {
        uint32_t count;
        std::memcpy(&count, b.data() + at, 4);
        if (uint64_t(count) > uint64_t(end_pos - grid_pos)) {
          fail("grid " + std::to_string(i) + ": its delayed-loading metadata counts " + std::to_string(count) +
               " nodes in " + std::to_string(end_pos - grid_pos) + " bytes: corrupt");
        }
      }
      at += n;
    }
    if (at > size_t(block_pos)) fail("grid " + std::to_string(i) + "'s metadata runs past its data's start: corrupt");
    (void)next;
    at = size_t(end_pos);
  }
}

#ifdef CAUSTICA_OPENVDB

bool vdb_supported() { return true; }

namespace {

void initialise_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// The grid's values over `box` (index space, inclusive) into out.values, x fastest.
template <class GridT, class Get>
void copy_dense(const GridT& grid, const openvdb::CoordBBox& box, VolumeGrid& out, Get get) {
  auto acc = grid.getConstAccessor();
  const openvdb::Coord lo = box.min();
  out.values.resize(size_t(out.nx) * size_t(out.ny) * size_t(out.nz) * size_t(out.channels));
  size_t i = 0;
  for (int z = 0; z < out.nz; ++z)
    for (int y = 0; y < out.ny; ++y)
      for (int x = 0; x < out.nx; ++x, i += size_t(out.channels)) get(acc.getValue(lo.offsetBy(x, y, z)), &out.values[i]);
}

// The reading itself, in the child process (no threads: OpenVDB's serial paths only).
VolumeGrid read_vdb_here(const std::string& path, const std::string& grid_name) {
  auto fail = [&](const std::string& m) -> void { throw InputError(path + ": " + m); };
  initialise_openvdb();
  openvdb::GridBase::Ptr base;
  try {
    openvdb::io::File file(path);
    file.open(false);  // read everything now (no memory-mapped delayed loading)
    std::string name = grid_name;
    if (name.empty()) {
      if (file.hasGrid("density")) name = "density";
      else {
        for (auto it = file.beginName(); it != file.endName(); ++it) {
          const openvdb::GridBase::ConstPtr meta = file.readGridMetadata(it.gridName());
          if (meta->isType<openvdb::FloatGrid>() || meta->isType<openvdb::DoubleGrid>() || meta->isType<openvdb::Vec3SGrid>()) {
            name = it.gridName();
            break;
          }
        }
      }
      if (name.empty()) fail("holds no float or vector grid");
    } else if (!file.hasGrid(name)) {
      std::string known;
      for (auto it = file.beginName(); it != file.endName(); ++it) known += (known.empty() ? "" : ", ") + it.gridName();
      fail("has no grid named \"" + name + "\" (it has: " + (known.empty() ? "none" : known) + ")");
    }
    base = file.readGrid(name);
    file.close();
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    fail(std::string("not a readable OpenVDB file (") + e.what() + ")");
  }
  if (base->getGridClass() == openvdb::GRID_LEVEL_SET) {
    fail("grid \"" + base->getName() + "\" is a level set (signed distances), not a density (a fog volume)");
  }
  if (!base->transform().isLinear()) fail("grid \"" + base->getName() + "\" has a non-linear (frustum) transform");
  VolumeGrid g;
  openvdb::CoordBBox box;
  // The active voxels' box (by a serial walk: OpenVDB's own evaluation runs threads), one voxel
  // of background around it (the density falls to it), copied dense: `put` stores a value's
  // `channels` floats.
  auto read = [&](const auto& grid, int channels, auto put) {
    for (auto it = grid.cbeginValueOn(); it; ++it) {
      openvdb::CoordBBox b;
      it.getBoundingBox(b);
      box.expand(b);
    }
    if (box.empty()) fail("grid \"" + base->getName() + "\" has no active voxels");
    box.expand(1);
    const openvdb::Coord dim = box.dim();
    g.nx = dim.x();
    g.ny = dim.y();
    g.nz = dim.z();
    g.channels = channels;
    const uint64_t voxels = uint64_t(g.nx) * uint64_t(g.ny) * uint64_t(g.nz);
    if (voxels > kMaxVoxels) fail("grid \"" + base->getName() + "\" spans " + std::to_string(voxels) + " voxels, more than the 2^30 read");
    copy_dense(grid, box, g, put);
  };
  if (auto fg = openvdb::gridConstPtrCast<openvdb::FloatGrid>(base)) {
    read(*fg, 1, [](float v, float* o) { o[0] = v; });
  } else if (auto dg = openvdb::gridConstPtrCast<openvdb::DoubleGrid>(base)) {
    read(*dg, 1, [](double v, float* o) { o[0] = float(v); });
  } else if (auto vg = openvdb::gridConstPtrCast<openvdb::Vec3SGrid>(base)) {
    read(*vg, 3, [](const openvdb::Vec3s& v, float* o) { o[0] = v.x(), o[1] = v.y(), o[2] = v.z(); });
  } else {
    fail("grid \"" + base->getName() + "\" holds " + base->valueType() + " values; float, double or vec3s grids are read");
  }
  for (size_t i = 0; i < g.values.size(); ++i) {
    const float v = g.values[i];
    if (!std::isfinite(v) || v < 0.0f) {
      const size_t voxel = i / size_t(g.channels);
      const openvdb::Coord c = box.min().offsetBy(int(voxel % size_t(g.nx)), int(voxel / size_t(g.nx) % size_t(g.ny)),
                                                  int(voxel / size_t(g.nx) / size_t(g.ny)));
      std::ostringstream m;
      m << "grid \"" << base->getName() << "\": voxel (" << c.x() << ", " << c.y() << ", " << c.z() << ") holds " << v
        << "; values must be finite and not negative";
      fail(m.str());
    }
  }
  // Index space: voxel (i, j, k) at (i, j, k); the box spans the copied voxels corner to corner.
  g.box.lo = Vec3(float(box.min().x()), float(box.min().y()), float(box.min().z()));
  g.box.hi = Vec3(float(box.max().x()), float(box.max().y()), float(box.max().z()));
  // OpenVDB's matrices act on row vectors (the translation in the last row): element (r, c) of
  // its matrix is glm's column r, row c.
  const openvdb::Mat4d m = base->transform().baseMap()->getAffineMap()->getMat4();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) g.to_world[r][c] = float(m(r, c));
  return g;
}

// Sends a grid, or an error, down a pipe: a status byte, then the message, or the sizes, box,
// transform and values.
void send_grid(int fd, const VolumeGrid* g, const std::string& error) {
  std::string out(1, g ? '\1' : '\0');
  auto put = [&](const void* p, size_t n) { out.append(static_cast<const char*>(p), n); };
  if (g) {
    const int32_t head[4] = {g->nx, g->ny, g->nz, g->channels};
    put(head, sizeof(head));
    put(&g->box.lo, 12);
    put(&g->box.hi, 12);
    put(&g->to_world[0][0], 64);
    put(g->values.data(), g->values.size() * 4);
  } else {
    out += error;
  }
  for (size_t done = 0; done < out.size();) {
    const ssize_t n = ::write(fd, out.data() + done, out.size() - done);
    if (n <= 0) return;
    done += size_t(n);
  }
}

}  // namespace

VolumeGrid read_vdb_file(const std::string& path, const std::string& grid_name) {
  auto fail = [&](const std::string& m) -> void { throw InputError(path + ": " + m); };
  // OpenVDB's reader trusts what a file says: a truncated or corrupt one can make it allocate
  // without end, loop, or corrupt memory. The structure is checked here first, and the file is
  // then read in a child process under a memory limit and a time limit: whatever OpenVDB does
  // with a bad file ends there, as an error naming the file.
  const std::string bytes = read_file_bytes(path, "grid file");
  check_vdb_structure(bytes, path);
  int fds[2];
  if (::pipe(fds) != 0) fail("cannot make a pipe to read the grid");
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]), ::close(fds[1]);
    fail("cannot start the process that reads the grid");
  }
  if (pid == 0) {
    ::close(fds[0]);
    // The address space now, plus room for the file's grid (at most 2^30 voxels of 3 floats).
    long pages = 0;
    if (FILE* f = std::fopen("/proc/self/statm", "r")) {
      if (std::fscanf(f, "%ld", &pages) != 1) pages = 0;
      std::fclose(f);
    }
    const uint64_t now = uint64_t(pages) * uint64_t(::sysconf(_SC_PAGESIZE));
    const uint64_t room = (uint64_t(16) << 30) + 64 * uint64_t(bytes.size());
    const rlimit limit{rlim_t(now + room), rlim_t(now + room)};
    ::setrlimit(RLIMIT_AS, &limit);
    try {
      const VolumeGrid g = read_vdb_here(path, grid_name);
      send_grid(fds[1], &g, "");
    } catch (const std::bad_alloc&) {
      send_grid(fds[1], nullptr, path + ": corrupt: reading it asks for more memory than the file could need");
    } catch (const std::exception& e) {
      send_grid(fds[1], nullptr, e.what());
    }
    ::close(fds[1]);
    ::_exit(0);
  }
  ::close(fds[1]);
  // A minute, and a second more per megabyte of file.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60 + bytes.size() / 1000000);
  std::string got;
  char buffer[65536];
  bool timed_out = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int r = ::poll(&p, 1, int(std::min<long long>(left, 1000)));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof(buffer));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    got.append(buffer, size_t(n));
  }
  ::close(fds[0]);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out) fail("corrupt: OpenVDB's reader did not finish with it within the time limit");
  if (WIFSIGNALED(status)) fail("corrupt: OpenVDB's reader failed on it (signal " + std::to_string(WTERMSIG(status)) + ")");
  if (got.empty()) fail("corrupt: OpenVDB's reader ended without a result");
  if (got[0] == '\0') throw InputError(got.substr(1));
  // The child's grid, checked for size before use.
  VolumeGrid g;
  constexpr size_t kHead = 1 + 16 + 24 + 64;
  if (got.size() < kHead) fail("the reading process sent a short result");
  int32_t head[4];
  std::memcpy(head, got.data() + 1, 16);
  g.nx = head[0], g.ny = head[1], g.nz = head[2], g.channels = head[3];
  std::memcpy(&g.box.lo, got.data() + 17, 12);
  std::memcpy(&g.box.hi, got.data() + 29, 12);
  std::memcpy(&g.to_world[0][0], got.data() + 41, 64);
  const uint64_t values = uint64_t(std::max(g.nx, 0)) * uint64_t(std::max(g.ny, 0)) * uint64_t(std::max(g.nz, 0)) *
                          uint64_t(std::max(g.channels, 0));
  if (values == 0 || got.size() != kHead + 4 * values) fail("the reading process sent a result of the wrong size");
  g.values.resize(size_t(values));
  std::memcpy(g.values.data(), got.data() + kHead, size_t(values) * 4);
  return g;
}

void write_vdb_file(const std::string& path, const VolumeGrid& grid, const std::string& name) {
  initialise_openvdb();
  openvdb::FloatGrid::Ptr out = openvdb::FloatGrid::create(0.0f);
  out->setName(name);
  out->setGridClass(openvdb::GRID_FOG_VOLUME);
  auto acc = out->getAccessor();
  size_t i = 0;
  for (int z = 0; z < grid.nz; ++z)
    for (int y = 0; y < grid.ny; ++y)
      for (int x = 0; x < grid.nx; ++x, i += size_t(grid.channels))
        if (grid.values[i] != 0.0f) acc.setValue(openvdb::Coord(x, y, z), grid.values[i]);
  // Index (0, 0, 0) at box.lo, (n - 1) at box.hi, per axis.
  const Vec3 step = grid.box.extent() / Vec3(float(std::max(grid.nx - 1, 1)), float(std::max(grid.ny - 1, 1)),
                                            float(std::max(grid.nz - 1, 1)));
  openvdb::Mat4d m = openvdb::Mat4d::identity();
  m.setToScale(openvdb::Vec3d(step.x, step.y, step.z));
  m.setTranslation(openvdb::Vec3d(grid.box.lo.x, grid.box.lo.y, grid.box.lo.z));
  out->setTransform(openvdb::math::Transform::createLinearTransform(m));
  openvdb::io::File file(path);
  file.write({out});
  file.close();
}

#else

bool vdb_supported() { return false; }

VolumeGrid read_vdb_file(const std::string& path, const std::string&) {
  throw InputError(path + ": this build of Caustica reads no OpenVDB files (configure with CAUSTICA_OPENVDB=ON; Debian: libopenvdb-dev)");
}

void write_vdb_file(const std::string& path, const VolumeGrid&, const std::string&) {
  throw InputError(path + ": this build of Caustica writes no OpenVDB files (CAUSTICA_OPENVDB is off)");
}

#endif

}  // namespace caustica
