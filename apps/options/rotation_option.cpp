// Implementation of --rotate DEG|auto.
#include "options/rotation_option.hpp"

#include <cstdio>

#include "lighting/best_rotation.hpp"
#include "options/number_or_auto.hpp"

namespace relume {

CLI::Option* add_rotation_option(CLI::App& command, std::string& rotate, const std::string& help) {
  return command
      .add_option("--rotate", rotate,
                  help +
                      "; auto: the rotation that leaves the least of the map's energy outside "
                      "the light set")
      ->capture_default_str()
      ->check(number_or_auto("--rotate", "degrees"));
}

double parse_rotation_degrees(const std::string& text) {
  return parse_finite_number(text, "--rotate", "degrees");
}

ResolvedRotation resolve_rotation(const std::string& rotate,
                                  const LightVectorIntegrator& integrator) {
  const bool automatic = rotate == "auto";
  ResolvedRotation resolved;
  resolved.degrees = automatic ? 0 : parse_rotation_degrees(rotate);
  const LightVector asked = integrator.integrate(resolved.degrees);
  if (!automatic && asked.outside_fraction() <= 0.01) {
    resolved.information = describe_coverage(asked);
    return resolved;
  }
  const BestRotation best = find_best_rotation(integrator);
  char text[256];
  if (automatic) {
    resolved.degrees = best.degrees;
    std::snprintf(text, sizeof text, " (%.2f%% at 0 degrees)", 100 * asked.outside_fraction());
    char chose[64];
    std::snprintf(chose, sizeof chose, "--rotate auto chose %g degrees: ", best.degrees);
    resolved.information = chose + describe_coverage(integrator.integrate(best.degrees)) + text;
  } else if (best.outside_fraction < asked.outside_fraction() - 0.01) {
    std::snprintf(text, sizeof text, "; --rotate %g would leave %.2f%% outside (--rotate auto)",
                  best.degrees, 100 * best.outside_fraction);
    resolved.information = describe_coverage(asked) + text;
  } else {
    resolved.information = describe_coverage(asked) + " (no rotation leaves clearly less outside)";
  }
  return resolved;
}

}  // namespace relume
