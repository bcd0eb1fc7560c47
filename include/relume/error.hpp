// relume/error.hpp: the exception types relume throws. Error, for bad input or failed operations:
// its message names the file, line or value at fault and what was expected; the `relume` command
// prints it and exits with status 1. Interrupted, an Error, when long work stopped because an
// interruption was requested (a signal handler, or a progress callback that asked to stop): the
// work's result is thrown away whole, nothing is left half done.
#pragma once

#include <stdexcept>
#include <string>

namespace relume {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Interrupted : public Error {
 public:
  Interrupted() : Error("interrupted") {}
};

}  // namespace relume
