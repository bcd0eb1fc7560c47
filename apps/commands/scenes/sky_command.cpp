// `relume sky`: writes the built-in procedural sky (lat-long HDR) for demos and tests.
#include <relume/image.hpp>
#include <relume/lighting.hpp>

#include "command_registry.hpp"
#include "options/output_paths.hpp"

namespace relume {
namespace {

const CommandRegistration registration{
    15, [](CLI::App& app) {
      auto options = std::make_shared<SkyOptions>();
      auto output = std::make_shared<std::string>();
      auto* command = app.add_subcommand(
          "sky",
          "Write a built-in HDR sky (lat-long, sun + sky gradient + ground) to use with --env");
      command->add_option("-o,--output", *output, "Output map (.exr or .hdr for HDR)")->required();
      command->add_option("--width", options->width, "Map width; height is width/2")
          ->capture_default_str();
      command
          ->add_option("--sun-elevation", options->sun_elevation_deg,
                       "Sun elevation above the horizon, degrees")
          ->capture_default_str();
      command
          ->add_option("--sun-azimuth", options->sun_azimuth_deg,
                       "Sun azimuth about +y, degrees from straight ahead (-z) towards +x")
          ->capture_default_str();
      command->add_option("--sun-radiance", options->sun_radiance, "Radiance inside the sun's disc")
          ->capture_default_str();
      command->callback([options, output] {
        check_new_output(*output);
        write_image(*output, render_sky(*options));
      });
    }};

}  // namespace
}  // namespace relume
