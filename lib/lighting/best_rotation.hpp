// The rotation of an environment map about the up axis that puts the most of its energy on a
// light set (--rotate auto): a light set that covers part of the sphere (DiLiGenT's front
// hemisphere) sees only part of any map, and which part depends on the rotation.
#pragma once

#include <relume/lighting.hpp>

namespace relume {

struct BestRotation {
  double degrees = 0;           // in [0, 360)
  double outside_fraction = 0;  // of the map's energy outside the light set at `degrees`
};

// Tries every 5 degrees of the whole turn, then every degree between those around the best; among
// equal fractions the smallest angle wins. Costs 80 integrations
// (LightVectorIntegrator::integrate).
BestRotation find_best_rotation(const LightVectorIntegrator& integrator);

}  // namespace relume
