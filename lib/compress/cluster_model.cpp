// Implementation of the clustering working state helpers (see cluster_model.hpp).
#include "compress/cluster_model.hpp"

#include <cmath>
#include <relume/error.hpp>

#include "core/parallel.hpp"
#include "model/haar_transform.hpp"

namespace relume {

std::vector<std::vector<std::uint32_t>> ClusterModel::members() const {
  std::vector<std::vector<std::uint32_t>> lists(static_cast<std::size_t>(clusters));
  for (std::size_t r = 0; r < assignment.size(); ++r)
    lists[static_cast<std::size_t>(assignment[r])].push_back(static_cast<std::uint32_t>(r));
  return lists;
}

PreparedRows prepare_rows(const ReflectanceField& field, bool haar_transform, float noise_floor,
                          unsigned threads, const std::vector<float>& light_scale) {
  const int lights = field.lights();
  if (!light_scale.empty() && (haar_transform || int(light_scale.size()) != lights))
    throw Error("a light scale needs one value per light (" + std::to_string(lights) +
                ") and no basis transform");
  const bool masked = !field.mask.empty();
  if (masked && std::int64_t(field.mask.size()) != field.pixels())
    throw Error("field mask has " + std::to_string(field.mask.size()) + " pixels, expected " +
                std::to_string(field.pixels()));
  PreparedRows prepared;
  const double floor_energy = double(noise_floor) * noise_floor * lights;
  std::vector<double> dark_sum(std::size_t(field.channels) * lights, 0.0);
  for (std::int64_t q = 0; q < field.pixels(); ++q) {
    if (masked && field.mask[std::size_t(q)] == 0) continue;
    bool dark = noise_floor > 0;
    const std::size_t first = prepared.functions.size();
    for (int c = 0; c < field.channels; ++c) {
      const std::int64_t p = q * field.channels + c;
      const auto row = field.values.row(p);
      double energy = 0;
      for (int i = 0; i < lights; ++i) {
        if (!std::isfinite(row[i]))
          throw Error("reflectance function " + std::to_string(p) + " (pixel " + std::to_string(q) +
                      ", channel " + std::to_string(c) + ") has a non-finite value " +
                      std::to_string(row[i]) + " at light " + std::to_string(i));
        energy += double(row[i]) * row[i];
      }
      dark = dark && energy <= floor_energy;
      if (energy > 0) prepared.functions.push_back(static_cast<std::uint32_t>(p));
    }
    if (!dark) continue;
    prepared.functions.resize(first);  // the pixel's functions go to the dark model instead
    prepared.dark_pixels.push_back(static_cast<std::uint32_t>(q));
    for (int c = 0; c < field.channels; ++c)
      for (int i = 0; i < lights; ++i)
        dark_sum[std::size_t(c) * lights + i] += field.values(q * field.channels + c, i);
  }
  if (!prepared.dark_pixels.empty()) {
    prepared.dark.resize(dark_sum.size());
    for (std::size_t v = 0; v < dark_sum.size(); ++v)
      prepared.dark[v] = float(dark_sum[v] / double(prepared.dark_pixels.size()));
    if (haar_transform)
      for (int c = 0; c < field.channels; ++c)
        haar_forward(prepared.dark.data() + std::size_t(c) * lights, lights, 1);
  }
  prepared.light_scale = light_scale;
  WorkingRows& rows = prepared.rows;
  rows.values.resize(static_cast<Eigen::Index>(prepared.functions.size()), lights);
  rows.norms.resize(prepared.functions.size());
  parallel_for(prepared.functions.size(), threads, [&](std::size_t r, unsigned) {
    auto out = rows.values.row(static_cast<Eigen::Index>(r));
    out = field.values.row(prepared.functions[r]);
    for (std::size_t i = 0; i < light_scale.size(); ++i) out[Eigen::Index(i)] /= light_scale[i];
    if (haar_transform) haar_forward(out.data(), lights, 1);
    const double norm = out.cast<double>().norm();
    rows.norms[r] = static_cast<float>(norm);
    out *= static_cast<float>(1.0 / norm);
  });
  return prepared;
}

}  // namespace relume
