// Implementation of the one-basis model's rate fitting (see global_basis_rate.hpp).
#include "compress/global_basis_rate.hpp"

#include <algorithm>
#include <cmath>

#include "compress/global_basis.hpp"
#include "container/container.hpp"
#include "container/weight_plane_coding.hpp"
#include "core/interruption.hpp"

namespace relume {
namespace {

// The fewest codestream bytes tried: below this the planes are a few DC values.
constexpr std::uint64_t min_plane_bytes = 512;
// A PSNR target's bisection stops when its two ends are this close in bytes.
constexpr double bisection_ratio = 1.005;

class PlanesCurve {
 public:
  PlanesCurve(const ReflectanceField& original, CompressedField base, const RateTarget& target,
              const ContainerOptions& container, unsigned threads)
      : original_(original),
        base_(std::move(base)),
        target_(target),
        container_(container),
        threads_(threads) {
    // The container's bytes besides the codestream: those of a one-byte stand-in, less that byte.
    CompressedField stand_in = base_;
    stand_in.coded_weights = {{0}, 1.0f};
    fixed_bytes_ = plan_container(stand_in, container_).file_bytes - 1;
  }

  std::uint64_t fixed_bytes() const { return fixed_bytes_; }

  // The field with its planes coded in at most `plane_bytes`, measured.
  // A safe point for SIGINT / SIGTERM before each coding (a few seconds each on a whole frame).
  std::pair<CompressedField, PlanesRatePoint> measure(std::uint64_t plane_bytes) {
    throw_if_interrupted();
    CompressedField field = base_;
    code_weights_as_planes(field, plane_bytes, threads_);
    PlanesRatePoint point;
    point.plane_bytes = field.coded_weights.codestream.size();
    const StoredMeasure stored = measure_stored(original_, field, target_, container_, threads_);
    point.bytes = stored.bytes;
    point.error = stored.error;
    point.psnr = stored.psnr;
    points_.push_back(point);
    return {std::move(field), point};
  }

  const std::vector<PlanesRatePoint>& points() const { return points_; }

 private:
  const ReflectanceField& original_;
  CompressedField base_;
  const RateTarget& target_;
  const ContainerOptions& container_;
  unsigned threads_;
  std::uint64_t fixed_bytes_ = 0;
  std::vector<PlanesRatePoint> points_;
};

// The largest codestream whose container fits `bytes`: first the bytes left after the fixed
// sections, then corrected by what the container came to (zstd may shave the codestream's
// headers; the header's step has a few more or fewer digits), keeping the largest that fits.
GlobalBasisFit fit_bytes(PlanesCurve& curve, std::uint64_t bytes) {
  GlobalBasisFit fit;
  std::uint64_t plane_bytes =
      bytes > curve.fixed_bytes() + min_plane_bytes ? bytes - curve.fixed_bytes() : min_plane_bytes;
  for (int attempt = 0; attempt < 4; ++attempt) {
    auto [field, point] = curve.measure(plane_bytes);
    const bool met = point.bytes <= bytes;
    // The first point, a fit where there was none, or a larger fit.
    if (attempt == 0 || (met && (!fit.met || point.bytes > fit.point.bytes)) ||
        (!met && !fit.met && point.bytes < fit.point.bytes))
      fit = {std::move(field), point, met, {}};
    if ((met && double(point.bytes) >= 0.995 * double(bytes)) ||
        (!met && plane_bytes == min_plane_bytes))
      break;
    const auto shortfall = std::int64_t(bytes) - std::int64_t(point.bytes);
    plane_bytes = std::uint64_t(std::max<std::int64_t>(
        std::int64_t(min_plane_bytes), std::int64_t(plane_bytes) + shortfall - (met ? 16 : 0)));
  }
  return fit;
}

// The fewest codestream bytes whose PSNR reaches `psnr`, by bisection on the bytes (in their
// logarithm) between the fewest tried and the planes' raw 16-bit size.
GlobalBasisFit reach_psnr(PlanesCurve& curve, double psnr, std::uint64_t raw_bytes) {
  GlobalBasisFit fit;
  std::uint64_t lo = min_plane_bytes, hi = std::max(raw_bytes, 2 * min_plane_bytes);
  auto [low_field, low] = curve.measure(lo);
  if (low.psnr >= psnr) return {std::move(low_field), low, true, {}};
  auto [high_field, high] = curve.measure(hi);
  if (high.psnr < psnr) return {std::move(high_field), high, false, {}};
  fit = {std::move(high_field), high, true, {}};
  while (double(hi) > bisection_ratio * double(lo)) {
    const auto mid = std::uint64_t(std::sqrt(double(lo) * double(hi)));
    auto [field, point] = curve.measure(mid);
    if (point.psnr >= psnr) {
      hi = mid;
      if (point.bytes < fit.point.bytes) fit = {std::move(field), point, true, {}};
    } else {
      lo = mid;
    }
  }
  return fit;
}

}  // namespace

std::vector<int> global_basis_sizes(int lights) {
  std::vector<int> sizes;
  for (int k : {4, 8, 16, 24, 32, 48, 64, 96, 128, 192, 256, 384, 512, 768, 1024})
    if (k < lights) sizes.push_back(k);
  sizes.push_back(lights);
  return sizes;
}

GlobalBasisFit fit_global_basis(const ReflectanceField& field, const Eigen::MatrixXd& directions,
                                int terms, const RateTarget& target,
                                const ContainerOptions& container, unsigned threads) {
  PlanesCurve curve(field, global_basis_field(field, directions, terms), target, container,
                    threads);
  const std::uint64_t raw_bytes =
      2 * std::uint64_t(field.channels) * std::uint64_t(terms) * std::uint64_t(field.pixels());
  GlobalBasisFit fit =
      target.bytes > 0 ? fit_bytes(curve, target.bytes) : reach_psnr(curve, target.psnr, raw_bytes);
  fit.points = curve.points();
  return fit;
}

}  // namespace relume
