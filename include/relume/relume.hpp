// relume/relume.hpp: the whole public API of the relume library in one include.
//
//   #include <relume/relume.hpp>
//   relume::ReflectanceField field = relume::load_field("scene");        // folder or .lp file
//   relume::CompressedField compressed = relume::compress(field, {.clusters = 64, .terms = 4});
//   relume::write_container("scene.relume", compressed);
//   relume::EnvironmentMap sky = relume::load_environment_map("sky.exr");
//   relume::LightRgb light = relume::integrate_light_vector(sky, compressed.directions, 0).rgb;
//   relume::Relighter relighter(compressed);                             // OpenCL
//   relume::write_image("relit.exr", relighter.relight(light));
//
// CMake: find_package(relume REQUIRED) and target_link_libraries(app PRIVATE relume::relume).
// Every function throws relume::Error with a message that names the file or value at fault.
#pragma once

#include <relume/compress.hpp>          // compress(): clustered sparse residual factorization
#include <relume/compressed_field.hpp>  // CompressedField, reconstruct_field, relative_error
#include <relume/container.hpp>         // .relume files: write_container, read_container
#include <relume/error.hpp>             // Error
#include <relume/field.hpp>             // ReflectanceField, load_field
#include <relume/image.hpp>             // Image, read_image, write_image
#include <relume/lighting.hpp>          // environment maps, light vectors, the built-in sky
#include <relume/relight.hpp>           // Relighter (OpenCL), CPU reference relighting
#include <relume/residual_budget.hpp>   // ResidualBudget: residual entries kept per function
#include <relume/version.hpp>           // version(), git_commit()
