// Whole-file reads for the scene readers: every failure an InputError naming the file.
#pragma once
#include <string>

namespace caustica {

// The bytes of the file at `path`; `what` names it in messages ("grid file"):
// "<path>: cannot open the grid file", "<path>: error while reading the grid file".
std::string read_file_bytes(const std::string& path, const std::string& what);

}  // namespace caustica
