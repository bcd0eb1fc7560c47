// The relume Python module: the C++ library's public API on NumPy arrays (see python/relume.pyi
// for the whole interface with types, and README's "Python" section).
#include <pybind11/pybind11.h>

#include <relume/version.hpp>

#include "bindings.hpp"
#include "errors.hpp"

PYBIND11_MODULE(relume, module) {
  using namespace relume::python;
  module.doc() = R"(relume: compression and relighting of fixed-viewpoint reflectance fields.

A reflectance field is a stack of one-light-at-a-time photographs: a float32 array
(height, width, channels, lights) with the light directions (lights, 3). relume compresses
it by clustered sparse residual factorization and relights the result under any light
vector (one RGB row per light, for example an environment map integrated by light_vector).

    import relume
    field = relume.load("scene")                      # a field folder or an .lp file
    compressed = relume.compress(field, clusters=64, terms=4, residual="5%")
    light = relume.light_vector(field.directions, "sky.exr", rotate=90)
    image = compressed.relight(light)                 # (height, width, channels) float32
    compressed.save("scene.relume")

Errors raise relume.Error (a ValueError) or relume.FileError (also an OSError) with
relume's message; Ctrl-C stops a compress or factor with KeyboardInterrupt.)";
  module.attr("__version__") = relume::version();
  module.attr("version_line") = relume::version_line();
  bind_errors(module);
  bind_images(module);
  bind_field(module);
  bind_lighting(module);
  bind_compressed(module);
  bind_compress(module);
  bind_factor(module);
}
