#include "io/file_bytes.h"
#include <fstream>
#include <sstream>
#include "core/error.h"

namespace caustica {

std::string read_file_bytes(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the " + what);
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(path + ": error while reading the " + what);
  return ss.str();
}

}  // namespace caustica
