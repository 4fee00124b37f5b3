// How much memory this process may still take, and the check made before a large allocation
// (a film's sums, photon maps, an inflated mesh, an image a file declares): a clear message that
// says how much is needed and what limits it, instead of std::bad_alloc or the OOM killer.
#pragma once
#include <cstdint>
#include <string>

namespace caustica {

struct MemoryLimit {
  uint64_t bytes = 0;  // what this process may still allocate
  std::string what;    // which limit that is, for messages: "the address-space limit (ulimit -v)"
};

// The smallest of: the address-space and data-segment limits (RLIMIT_AS, RLIMIT_DATA) less what
// the process has mapped, its cgroup's memory limit (cgroup v2 memory.max or v1
// memory.limit_in_bytes) less the cgroup's usage, and this machine's physical memory.
MemoryLimit memory_limit();

// Throws InputError "<what> needs about 12.9 GiB of memory; <limit> leaves 4.0 GiB<hint>" when
// `bytes` exceeds 90 % of memory_limit(). `hint` follows the message: " (use fewer photons)".
void check_memory(double bytes, const std::string& what, const std::string& hint = "");

std::string format_gib(double bytes);  // "12.9 GiB" (or MiB below one GiB)

}  // namespace caustica
