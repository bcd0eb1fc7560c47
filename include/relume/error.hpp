// relume/error.hpp: the one exception type relume throws for bad input or failed operations. Its
// message names the file, line or value at fault and what was expected; the `relume` command
// prints it and exits with status 1.
#pragma once

#include <stdexcept>
#include <string>

namespace relume {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace relume
