// libFuzzer target for the Mitsuba XML reader: any bytes must load or throw InputError.
// Build and run with scripts/fuzz.sh xml (CMake option CAUSTICA_FUZZ, clang only).
#include <cstddef>
#include <cstdint>
#include <string>
#include "io/json_reader.h"
#include "io/scene_loader.h"

// The scene "lives" in a folder that does not exist: relative includes, meshes and textures
// cannot reach real files.
static const char* const kFile = "/nonexistent/caustica-fuzz/scene.xml";

extern "C" const char* __ubsan_default_options() { return "halt_on_error=1:print_stacktrace=1"; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // Input not starting with '<' goes to the JSON reader, which has its own target; the
  // dictionary and the seeds keep this one on XML.
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    caustica::MitsubaOptions options;
    options.xml.defines = {{"spp", "4"}, {"res", "16"}};
    caustica::LoadedScene loaded = caustica::parse_scene(text, kFile, "/nonexistent/caustica-fuzz", options);
    (void)loaded;
  } catch (const caustica::InputError&) {
  }
  return 0;
}
