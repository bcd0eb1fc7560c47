// The OpenCL C sources of kernels/*.cl, embedded at build time (see cmake/embed_kernels.cmake).
#pragma once

#include <map>
#include <string>

namespace relume {

// File name (for example "relight.cl") -> source text.
const std::map<std::string, std::string>& kernel_sources();

}  // namespace relume
