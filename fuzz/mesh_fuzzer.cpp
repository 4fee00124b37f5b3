// libFuzzer target for the mesh readers: the first byte picks the format (OBJ, PLY, Mitsuba
// .serialized), the rest is the file. Any bytes must read or throw InputError.
// Build and run with scripts/fuzz.sh mesh.
#include <unistd.h>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include "io/json_reader.h"
#include "io/meshes/mesh_file.h"

extern "C" const char* __ubsan_default_options() { return "halt_on_error=1:print_stacktrace=1"; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const int format = data[0] % 3;
  const std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    if (format == 2) {
      caustica::parse_serialized(bytes, "fuzz.serialized", data[0] / 3 % 3);
    } else if (format == 1) {
      caustica::parse_ply(bytes, "fuzz.ply");
    } else {
      // tinyobjloader reads files: one per process, rewritten each time.
      static const std::string file = "/tmp/caustica-mesh-fuzz-" + std::to_string(getpid()) + ".obj";
      {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out << bytes;
      }
      caustica::read_obj(file);
    }
  } catch (const caustica::InputError&) {
  }
  return 0;
}
