// Implementation of the clustering working state helpers (see cluster_model.hpp).
#include "compress/cluster_model.hpp"

#include <cmath>
#include <relume/error.hpp>

#include "compress/dark_pixels.hpp"
#include "core/parallel.hpp"
#include "core/value_scans.hpp"
#include "model/haar_transform.hpp"

namespace relume {

std::vector<std::vector<std::uint32_t>> ClusterModel::members() const {
  std::vector<std::vector<std::uint32_t>> lists(static_cast<std::size_t>(clusters));
  for (std::size_t r = 0; r < assignment.size(); ++r)
    lists[static_cast<std::size_t>(assignment[r])].push_back(static_cast<std::uint32_t>(r));
  return lists;
}

void check_finite_values(const ReflectanceField& field) {
  if (!field.mask.empty() && std::int64_t(field.mask.size()) != field.pixels())
    throw Error("field mask has " + std::to_string(field.mask.size()) + " pixels, expected " +
                std::to_string(field.pixels()));
  if (all_finite(field.values.data(), std::size_t(field.values.size()))) return;
  for (std::int64_t p = 0; p < field.functions(); ++p) {
    const std::int64_t q = p / field.channels;
    if (!field.mask.empty() && field.mask[std::size_t(q)] == 0) continue;
    for (int i = 0; i < field.lights(); ++i)
      if (!std::isfinite(field.values(p, i)))
        throw Error("reflectance function " + std::to_string(p) + " (pixel " + std::to_string(q) +
                    ", channel " + std::to_string(p % field.channels) +
                    ") has a non-finite value " + std::to_string(field.values(p, i)) +
                    " at light " + std::to_string(i));
  }
}

PreparedRows prepare_rows(const ReflectanceField& field, bool haar_transform,
                          const NoiseModel& noise, unsigned threads,
                          const std::vector<float>& light_scale) {
  const int lights = field.lights();
  if (!light_scale.empty() && (haar_transform || int(light_scale.size()) != lights))
    throw Error("a light scale needs one value per light (" + std::to_string(lights) +
                ") and no basis transform");
  const bool masked = !field.mask.empty();
  check_finite_values(field);
  PreparedRows prepared;
  DarkPixels dark = select_dark_pixels(field, noise, threads);
  std::vector<std::uint8_t> is_dark(std::size_t(field.pixels()), 0);
  for (const std::uint32_t q : dark.pixels) is_dark[q] = 1;
  for (std::int64_t q = 0; q < field.pixels(); ++q) {
    if ((masked && field.mask[std::size_t(q)] == 0) || is_dark[std::size_t(q)]) continue;
    for (int c = 0; c < field.channels; ++c) {
      const std::int64_t p = q * field.channels + c;
      if (field.values.row(p).squaredNorm() > 0)
        prepared.functions.push_back(static_cast<std::uint32_t>(p));
    }
  }
  if (!dark.pixels.empty()) {
    prepared.dark_pixels = std::move(dark.pixels);
    prepared.dark_gains = std::move(dark.gains);
    prepared.dark_gain_step = dark.gain_step;
    prepared.dark = noise.shape;
    if (haar_transform)
      for (int c = 0; c < field.channels; ++c)
        haar_forward(prepared.dark.data() + std::size_t(c) * lights, lights, 1);
  }
  prepared.light_scale = light_scale;
  WorkingRows& rows = prepared.rows;
  rows.values.resize(static_cast<Eigen::Index>(prepared.functions.size()), lights);
  rows.norms.resize(prepared.functions.size());
  rows.pixel.resize(prepared.functions.size());
  parallel_for(prepared.functions.size(), threads, [&](std::size_t r, unsigned) {
    auto out = rows.values.row(static_cast<Eigen::Index>(r));
    out = field.values.row(prepared.functions[r]);
    rows.pixel[r] = prepared.functions[r] / std::uint32_t(field.channels);
    for (std::size_t i = 0; i < light_scale.size(); ++i) out[Eigen::Index(i)] /= light_scale[i];
    if (haar_transform) haar_forward(out.data(), lights, 1);
    const double norm = out.cast<double>().norm();
    rows.norms[r] = static_cast<float>(norm);
    out *= static_cast<float>(1.0 / norm);
  });
  return prepared;
}

}  // namespace relume
