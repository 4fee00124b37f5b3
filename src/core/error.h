// The error for bad input of any kind (scene file, command line, image or mesh file): its
// message is for the user and names the file and the place in it.
#pragma once
#include <stdexcept>

namespace caustica {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace caustica
