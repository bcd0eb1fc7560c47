// Implementation of the reference field relighter.
#include <relume/error.hpp>
#include <relume/relight.hpp>

#include "core/parallel.hpp"

namespace relume {

Image relight_field(const ReflectanceField& field, const LightRgb& light_vector, unsigned threads) {
  if (light_vector.rows() != field.lights())
    throw Error("the light vector has " + std::to_string(light_vector.rows()) +
                " rows but the field has " + std::to_string(field.lights()) + " lights");
  Eigen::MatrixXd lights(field.lights(), field.channels);
  for (int c = 0; c < field.channels; ++c)
    lights.col(c) = field.channels == 1 ? light_vector.cast<double>().rowwise().mean()
                                        : light_vector.col(c).cast<double>().eval();
  Image image(field.width, field.height, field.channels);
  const std::size_t rows_per_task = 4096;
  const std::size_t functions = static_cast<std::size_t>(field.functions());
  parallel_for(
      (functions + rows_per_task - 1) / rows_per_task, threads, [&](std::size_t task, unsigned) {
        const std::size_t end = std::min(functions, (task + 1) * rows_per_task);
        for (std::size_t p = task * rows_per_task; p < end; ++p) {
          const int c = static_cast<int>(p % field.channels);
          image.pixels[p] = static_cast<float>(
              field.values.row(static_cast<Eigen::Index>(p)).cast<double>().dot(lights.col(c)));
        }
      });
  return image;
}

}  // namespace relume
