// libFuzzer target for the scene loader: any bytes must load or throw InputError, nothing else.
// Build and run with scripts/fuzz.sh (CMake option CAUSTICA_FUZZ, clang only).
#include <cstddef>
#include <cstdint>
#include <string>
#include "io/json_reader.h"
#include "io/scene_loader.h"

// A folder that does not exist, so "file" keys cannot reach real meshes through relative paths.
static const char* const kNoMeshDir = "/nonexistent/caustica-fuzz-no-meshes";

// Make UBSan reports fatal, so libFuzzer records them as crashes (the default only prints).
extern "C" const char* __ubsan_default_options() { return "halt_on_error=1:print_stacktrace=1"; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // parse_scene validates everything and builds the scene (BVH, lights) before returning.
    caustica::LoadedScene loaded = caustica::parse_scene(text, "fuzz.json", kNoMeshDir);
    (void)loaded;
  } catch (const caustica::InputError&) {
    // Rejected input is the expected outcome; any other exception escapes and aborts.
  }
  return 0;
}
