// Implementation of the double-precision reference relighter of compressed fields.
#include "relight/compressed_relight_reference.hpp"

#include <algorithm>
#include <cmath>
#include <relume/error.hpp>
#include <string>

#include "core/parallel.hpp"
#include "model/compressed_field_checks.hpp"
#include "model/haar_transform.hpp"
#include "model/reconstruct_field.hpp"

namespace relume {

void check_relightable(const CompressedField& field) {
  validate_compressed_field(field, "cannot relight the compressed field");
  if (field.channels != 1 && field.channels != 3)
    throw Error("cannot relight the compressed field: it has " + std::to_string(field.channels) +
                " channels (expected 1 or 3, the light vector being RGB)");
}

RowMatrixF light_in_field_basis(const CompressedField& field, const LightRgb& light) {
  if (light.rows() != field.lights)
    throw Error("the light vector has " + std::to_string(light.rows()) +
                " rows but the compressed field has " + std::to_string(field.lights) + " lights");
  for (Eigen::Index i = 0; i < light.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(light(i, c)))
        throw Error("light vector entry (light " + std::to_string(i) + ", channel " +
                    std::to_string(c) + ") is " + std::to_string(light(i, c)) +
                    " (expected a finite number)");
  RowMatrixF basis_light =
      field.channels == 1 ? RowMatrixF(light.rowwise().mean()) : RowMatrixF(light);
  if (field.transform == BasisTransform::haar)
    for (int c = 0; c < field.channels; ++c)
      haar_forward(basis_light.data() + c, field.lights, field.channels);
  else if (field.transform != BasisTransform::identity)
    throw Error("compressed field: unknown basis transform " +
                std::to_string(int(field.transform)) + " (expected identity or haar)");
  return basis_light;
}

std::vector<double> cluster_light_products(const CompressedField& field,
                                           const RowMatrixF& basis_light) {
  std::vector<double> products(std::size_t(field.clusters) * field.terms * field.channels, 0.0);
  for (int k = 0; k < field.clusters; ++k)
    for (int j = 0; j < field.terms; ++j) {
      const float* basis_row = field.basis(k) + std::size_t(j) * field.lights;
      for (int c = 0; c < field.channels; ++c) {
        double sum = 0;
        for (int i = 0; i < field.lights; ++i) sum += double(basis_row[i]) * basis_light(i, c);
        products[(std::size_t(k) * field.terms + j) * field.channels + c] = sum;
      }
    }
  return products;
}

CompressedRelightReference::CompressedRelightReference(const CompressedField& field)
    : field_(field) {
  check_relightable(field_);
}

Image CompressedRelightReference::relight(const LightRgb& light, int residual_cap,
                                          RelightTerms terms, unsigned threads) const {
  check_residual_cap(residual_cap);
  const CompressedField& field = field_;
  const RowMatrixF basis_light = light_in_field_basis(field, light);
  const std::vector<double> products = terms == RelightTerms::all
                                           ? cluster_light_products(field, basis_light)
                                           : std::vector<double>();
  Image image(field.width, field.height, field.channels);
  const auto& residual = field.residual;
  const std::size_t rows = field.stored_rows();
  const std::size_t rows_per_task = 4096;
  parallel_for(
      (rows + rows_per_task - 1) / rows_per_task, threads, [&](std::size_t task, unsigned) {
        const std::size_t end = std::min(rows, (task + 1) * rows_per_task);
        for (std::size_t s = task * rows_per_task; s < end; ++s) {
          const std::uint32_t p = field.stored_function[s];
          const int c = int(p % std::uint32_t(field.channels));
          double sum = 0;
          if (terms == RelightTerms::all) {
            const double* v =
                products.data() + std::size_t(field.cluster[s]) * field.terms * field.channels;
            for (int j = 0; j < field.terms; ++j)
              sum += double(field.weights(Eigen::Index(s), j)) * v[j * field.channels + c];
          }
          const std::uint32_t begin = residual.row_offsets[s];
          const std::uint32_t used = std::min<std::uint32_t>(residual.row_offsets[s + 1] - begin,
                                                             std::uint32_t(residual_cap));
          for (std::uint32_t e = begin; e < begin + used; ++e)
            sum += double(residual.values[e]) * basis_light(residual.light_index[e], c);
          image.pixels[p] = static_cast<float>(sum);
        }
      });
  if (terms == RelightTerms::all && !field.dark_pixels.empty()) {
    const std::vector<double> dark = dark_light_products(field, basis_light);
    for (std::size_t d = 0; d < field.dark_pixels.size(); ++d)
      for (int c = 0; c < field.channels; ++c)
        image.pixels[std::size_t(field.dark_pixels[d]) * field.channels + c] =
            static_cast<float>(dark_gain(field, d, c) * dark[c]);
  }
  return image;
}

std::vector<double> dark_light_products(const CompressedField& field,
                                        const RowMatrixF& basis_light) {
  std::vector<double> products(field.dark.empty() ? 0 : field.channels, 0.0);
  for (std::size_t c = 0; c < products.size(); ++c)
    for (int i = 0; i < field.lights; ++i)
      products[c] += double(field.dark[c * field.lights + i]) * basis_light(i, int(c));
  return products;
}

Image relight_compressed_reference(const CompressedField& field, const LightRgb& light,
                                   int residual_cap, RelightTerms terms, unsigned threads) {
  return CompressedRelightReference(field).relight(light, residual_cap, terms, threads);
}

}  // namespace relume
