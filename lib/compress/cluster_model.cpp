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

PreparedRows prepare_rows(const ReflectanceField& field, bool haar_transform, unsigned threads) {
  const int lights = field.lights();
  const bool masked = !field.mask.empty();
  if (masked && std::int64_t(field.mask.size()) != field.pixels())
    throw Error("field mask has " + std::to_string(field.mask.size()) + " pixels, expected " +
                std::to_string(field.pixels()));
  PreparedRows prepared;
  for (std::int64_t p = 0; p < field.functions(); ++p) {
    if (masked && field.mask[std::size_t(p / field.channels)] == 0) continue;
    const auto row = field.values.row(p);
    bool nonzero = false;
    for (int i = 0; i < lights; ++i) {
      if (!std::isfinite(row[i]))
        throw Error("reflectance function " + std::to_string(p) + " (pixel " +
                    std::to_string(p / field.channels) + ", channel " +
                    std::to_string(p % field.channels) + ") has a non-finite value " +
                    std::to_string(row[i]) + " at light " + std::to_string(i));
      nonzero = nonzero || row[i] != 0.0f;
    }
    if (nonzero) prepared.functions.push_back(static_cast<std::uint32_t>(p));
  }
  WorkingRows& rows = prepared.rows;
  rows.values.resize(static_cast<Eigen::Index>(prepared.functions.size()), lights);
  rows.norms.resize(prepared.functions.size());
  parallel_for(prepared.functions.size(), threads, [&](std::size_t r, unsigned) {
    auto out = rows.values.row(static_cast<Eigen::Index>(r));
    out = field.values.row(prepared.functions[r]);
    if (haar_transform) haar_forward(out.data(), lights, 1);
    const double norm = out.cast<double>().norm();
    rows.norms[r] = static_cast<float>(norm);
    out *= static_cast<float>(1.0 / norm);
  });
  return prepared;
}

}  // namespace relume
