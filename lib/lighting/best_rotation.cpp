// The coarse-then-fine search for the rotation with the least energy outside the light set.
#include "lighting/best_rotation.hpp"

#include <cmath>

namespace relume {

BestRotation find_best_rotation(const LightVectorIntegrator& integrator) {
  BestRotation best{0, integrator.integrate(0).outside_fraction()};
  const auto consider = [&](double degrees) {
    const double wrapped = std::fmod(degrees + 360.0, 360.0);
    const double outside = integrator.integrate(wrapped).outside_fraction();
    if (outside < best.outside_fraction ||
        (outside == best.outside_fraction && wrapped < best.degrees))
      best = {wrapped, outside};
  };
  for (int degrees = 5; degrees < 360; degrees += 5) consider(degrees);
  const double coarse = best.degrees;
  for (int offset = -4; offset <= 4; ++offset)
    if (offset != 0) consider(coarse + offset);
  return best;
}

}  // namespace relume
