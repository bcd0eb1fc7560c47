// `relume view`: an interactive viewer in the browser. Serves a page on which the user drags a
// light across the object (or turns an environment map), sets exposure, residual cap and light
// colour, and sees the error of the cap or the stored pixels; every frame is relit on the server
// by the OpenCL relighter (apps/commands/view/, docs/viewer.md).
#include <memory>

#include "command_registry.hpp"
#include "options/renderer_options.hpp"
#include "commands/view/view_server.hpp"
#include "commands/view/viewer.hpp"

namespace relume {
namespace {

struct ViewOptions {
  ViewerSettings viewer;
  ServerSettings server;
};

void run_view(const ViewOptions& options) {
  check_renderer_options(options.viewer.renderer);
  Viewer viewer(options.viewer);
  serve_viewer(viewer, options.server);
}

const CommandRegistration registration{
    40, [](CLI::App& app) {
      auto options = std::make_shared<ViewOptions>();
      auto* command = app.add_subcommand(
          "view",
          "Serve an interactive viewer to a web browser: drag a light across the object or turn\n"
          "an environment map; every frame is relit on the server with OpenCL (docs/viewer.md).\n"
          "Example: relume view scene.relume --env sky.exr   (then open http://127.0.0.1:8080/)");
      command->add_option("input", options->viewer.input, "The .relume container")->required();
      command->add_option("--env", options->viewer.maps,
                          "Environment maps to light with (the page picks among them; the first "
                          "is the default light): lat-long, mirror ball or vertical cross");
      command
          ->add_option("--layout", options->viewer.layout,
                       "Layout of the maps: auto (from the aspect ratio), latlong, angular, cross")
          ->capture_default_str();
      add_renderer_options(*command, options->viewer.renderer);
      command
          ->add_option("--port", options->server.port,
                       "TCP port to listen on; 0 picks a free one (the address is printed)")
          ->capture_default_str()
          ->check(CLI::Range(0, 65535));
      command
          ->add_option("--host", options->server.host,
                       "Address to listen on; anything but loopback lets other machines connect "
                       "(a warning says so)")
          ->capture_default_str();
      command
          ->add_option("--max-requests", options->server.requests_per_second,
                       "Requests answered per second at most (a token bucket; more get HTTP 429)")
          ->capture_default_str()
          ->check(CLI::Range(1.0, 1e6));
      command->callback([options] { run_view(*options); });
    }};

}  // namespace
}  // namespace relume
