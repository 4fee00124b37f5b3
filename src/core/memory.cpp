// Memory limits from getrlimit, /proc and the cgroup file system.
#include "core/memory.h"
#include <sys/resource.h>
#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include "core/error.h"

namespace caustica {
namespace {

// A number from the first line of a file, or 0 when it is absent, unreadable or "max".
uint64_t read_number(const std::string& path) {
  std::ifstream in(path);
  unsigned long long v = 0;
  if (!(in >> v)) return 0;
  return v;
}

// The value of `key` in a cgroup's memory.stat ("key value" lines), or 0.
uint64_t read_stat(const std::string& path, const std::string& key) {
  std::ifstream in(path);
  std::string name;
  unsigned long long v = 0;
  while (in >> name >> v) {
    if (name == key) return v;
  }
  return 0;
}

// Field `index` (0-based) of /proc/self/statm, in bytes.
uint64_t statm_bytes(int index) {
  std::ifstream in("/proc/self/statm");
  unsigned long long v = 0;
  for (int i = 0; i <= index; ++i) {
    if (!(in >> v)) return 0;
  }
  return v * uint64_t(sysconf(_SC_PAGE_SIZE));
}

void consider(MemoryLimit& best, uint64_t limit, uint64_t used, const std::string& what) {
  const uint64_t left = limit > used ? limit - used : 0;
  if (left < best.bytes) best = {left, what};
}

// The cgroup's limit and usage: v2 (a "0::/path" line) or v1 (a "N:memory:/path" line). A
// container sees its own cgroup at the mount's root, so the root's files are tried too. The
// usage counts the page cache, whose inactive part the kernel gives back before it fails an
// allocation: that part is not counted as used.
void consider_cgroup(MemoryLimit& best) {
  std::ifstream in("/proc/self/cgroup");
  std::string line, v2, v1;
  while (std::getline(in, line)) {
    if (line.rfind("0::", 0) == 0) v2 = line.substr(3);
    const size_t at = line.find(":memory:");
    if (at != std::string::npos) v1 = line.substr(at + 8);
  }
  constexpr uint64_t kUnlimited = uint64_t(1) << 60;  // v1 writes about 2^63 for "no limit"
  auto try_dir = [&](const std::string& dir, const char* limit_file, const char* usage_file, const char* cache_key) {
    const uint64_t limit = read_number(dir + "/" + limit_file);
    if (limit == 0 || limit >= kUnlimited) return false;
    const uint64_t usage = read_number(dir + "/" + usage_file), cache = read_stat(dir + "/memory.stat", cache_key);
    consider(best, limit, usage > cache ? usage - cache : 0, std::string("the cgroup's memory limit (") + limit_file + ")");
    return true;
  };
  if (!v2.empty()) {
    if (try_dir("/sys/fs/cgroup" + v2, "memory.max", "memory.current", "inactive_file")) return;
    if (try_dir("/sys/fs/cgroup", "memory.max", "memory.current", "inactive_file")) return;
  }
  if (!v1.empty()) {
    if (try_dir("/sys/fs/cgroup/memory" + v1, "memory.limit_in_bytes", "memory.usage_in_bytes", "total_inactive_file")) return;
    try_dir("/sys/fs/cgroup/memory", "memory.limit_in_bytes", "memory.usage_in_bytes", "total_inactive_file");
  }
}

}  // namespace

MemoryLimit memory_limit() {
  MemoryLimit best{UINT64_MAX, ""};
  const double physical = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  if (physical > 0) consider(best, uint64_t(physical), statm_bytes(1), "this machine's memory");
  rlimit r{};
  if (getrlimit(RLIMIT_AS, &r) == 0 && r.rlim_cur != RLIM_INFINITY) {
    consider(best, uint64_t(r.rlim_cur), statm_bytes(0), "the address-space limit (ulimit -v)");
  }
  if (getrlimit(RLIMIT_DATA, &r) == 0 && r.rlim_cur != RLIM_INFINITY) {
    consider(best, uint64_t(r.rlim_cur), statm_bytes(5), "the data-segment limit (ulimit -d)");
  }
  consider_cgroup(best);
  return best;
}

std::string format_gib(double bytes) {
  char text[32];
  if (bytes >= double(1 << 30)) {
    std::snprintf(text, sizeof text, "%.1f GiB", bytes / double(1 << 30));
  } else {
    std::snprintf(text, sizeof text, "%.0f MiB", bytes / double(1 << 20));
  }
  return text;
}

void check_memory(double bytes, const std::string& what, const std::string& hint) {
  const MemoryLimit limit = memory_limit();
  if (limit.bytes == UINT64_MAX || bytes <= 0.9 * double(limit.bytes)) return;
  throw InputError(what + " needs about " + format_gib(bytes) + " of memory; " + limit.what + " leaves " +
                   format_gib(double(limit.bytes)) + hint);
}

}  // namespace caustica
