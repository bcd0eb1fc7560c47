// The consumer program of the install test, written only against the installed public headers:
// loads a synthetic field (written by the installed `relume synth`), compresses it, writes and
// reads its container, relights it under the built-in sky with OpenCL and with the CPU
// reference, and checks both against each other and against the uncompressed field relit.
// Prints the figures; exits 1 (with the reason) when a check fails.
#include <cmath>
#include <cstdio>
#include <relume/relume.hpp>

namespace {

// Relative squared difference sum (a - b)^2 / sum b^2 over all pixels.
double relative_difference(const relume::Image& a, const relume::Image& b) {
  double difference = 0, energy = 0;
  for (std::size_t i = 0; i < b.pixels.size(); ++i) {
    difference += double(a.pixels[i] - b.pixels[i]) * (a.pixels[i] - b.pixels[i]);
    energy += double(b.pixels[i]) * b.pixels[i];
  }
  return difference / energy;
}

int fail(const char* what, double value, double limit) {
  std::fprintf(stderr, "consumer: %s = %.3g, expected below %.3g\n", what, value, limit);
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: relume_consumer FIELD_FOLDER WORK_FOLDER\n");
    return 2;
  }
  try {
    const std::filesystem::path work = argv[2];
    const relume::ReflectanceField field = relume::load_field(argv[1]);
    relume::CompressOptions options;
    options.clusters = 8;
    options.terms = 3;
    options.residual = relume::ResidualBudget{4};
    options.threads = 2;
    relume::write_container(work / "scene.relume", relume::compress(field, options));
    const relume::CompressedField compressed = relume::read_container(work / "scene.relume");

    relume::SkyOptions sky_options;
    sky_options.width = 128;
    const relume::EnvironmentMap sky = relume::make_environment_map(
        relume::render_sky(sky_options), relume::EnvironmentLayout::latlong, "built-in sky");
    const relume::LightRgb light =
        relume::integrate_light_vector(sky, compressed.directions, 0).rgb;

    relume::Relighter opencl(compressed);
    const relume::Image relit = opencl.relight(light);
    relume::Relighter reference(compressed, {.cpu_reference = true});
    const relume::Image expected = reference.relight(light);
    const relume::Image uncompressed = relume::relight_field(field, light);
    relume::write_image(work / "relit.exr", relit);

    const double kernel_vs_reference = relative_difference(relit, expected);
    const double compressed_vs_field = relative_difference(expected, uncompressed);
    const double eq16 = relume::relative_error(field, compressed, true).mean;
    std::printf(
        "%s on %s: %d stored rows, Eq. 16 error %.4g; OpenCL vs reference %.3g; "
        "relit vs uncompressed %.3g\n",
        relume::version_line().c_str(), opencl.device_name().c_str(), int(compressed.stored_rows()),
        eq16, kernel_vs_reference, compressed_vs_field);
    if (compressed.stored_rows() == 0) return fail("stored rows", 0, 1);
    if (!(kernel_vs_reference < 1e-8))
      return fail("OpenCL vs reference", kernel_vs_reference, 1e-8);
    if (!(compressed_vs_field < 0.05))
      return fail("relit vs uncompressed", compressed_vs_field, 0.05);
    if (!(eq16 < 0.05)) return fail("Eq. 16 error", eq16, 0.05);
  } catch (const relume::Error& error) {
    std::fprintf(stderr, "consumer: %s\n", error.what());
    return 1;
  }
  return 0;
}
