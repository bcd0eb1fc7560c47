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
// A PSNR target's search stops when its two ends are this close in bytes.
constexpr double bracket_ratio = 1.005;

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

// A codestream whose container fits `bytes` and comes within 1.5% of them: aimed at 99.3% of the
// bytes (clear of both ends) after the fixed sections and the overhead learned from another
// size, then corrected by what the container came to (zstd shaves the codestream's markers, the
// header's step has more or fewer digits), keeping the largest that fits.
GlobalBasisFit fit_bytes(PlanesCurve& curve, std::uint64_t bytes, std::int64_t overhead) {
  constexpr double aim_share = 0.993, enough_share = 0.985;
  const double aim = aim_share * double(bytes);
  GlobalBasisFit fit;
  std::int64_t plane_bytes = std::llround(aim) - std::int64_t(curve.fixed_bytes()) - overhead;
  for (int attempt = 0; attempt < 4; ++attempt) {
    plane_bytes = std::max<std::int64_t>(plane_bytes, min_plane_bytes);
    auto [field, point] = curve.measure(std::uint64_t(plane_bytes));
    const bool met = point.bytes <= bytes;
    // The first point, a fit where there was none, or a larger fit.
    if (attempt == 0 || (met && (!fit.met || point.bytes > fit.point.bytes)) ||
        (!met && !fit.met && point.bytes < fit.point.bytes))
      fit = {std::move(field), point, met, {}, {}};
    if ((met && double(point.bytes) >= enough_share * double(bytes)) ||
        (!met && plane_bytes == std::int64_t(min_plane_bytes)))
      break;
    plane_bytes += std::llround(aim - double(point.bytes));
  }
  return fit;
}

// The fewest codestream bytes whose PSNR reaches `psnr`, between min_plane_bytes and the planes'
// raw 16-bit size: a bracket grown by factors of 4 from `guess` (another size's answer), then
// regula falsi on the logarithm of the bytes (in which the PSNR is nearly straight), with the
// Illinois halving so neither end sticks, until the ends are within bracket_ratio.
GlobalBasisFit reach_psnr(PlanesCurve& curve, double psnr, std::uint64_t raw_bytes,
                          std::uint64_t guess) {
  raw_bytes = std::max(raw_bytes, 2 * min_plane_bytes);
  GlobalBasisFit fit;   // the fewest bytes that reached it
  PlanesRatePoint low;  // the most bytes known not to reach it
  bool have_low = false;
  const auto try_bytes = [&](std::uint64_t plane_bytes) {
    auto [field, point] = curve.measure(plane_bytes);
    if (point.psnr >= psnr) {
      if (!fit.met || point.plane_bytes < fit.point.plane_bytes)
        fit = {std::move(field), point, true, {}, {}};
    } else if (!have_low || point.plane_bytes > low.plane_bytes) {
      low = point;
      have_low = true;
      if (!fit.met) fit = {std::move(field), point, false, {}, {}};
    }
    return point.psnr >= psnr;
  };
  std::uint64_t bytes = std::clamp(guess ? guess : raw_bytes / 64, min_plane_bytes, raw_bytes);
  if (try_bytes(bytes)) {
    while (!have_low && bytes > min_plane_bytes)
      try_bytes(bytes = std::max(min_plane_bytes, bytes / 4));
  } else {
    while (!fit.met && bytes < raw_bytes) try_bytes(bytes = std::min(raw_bytes, bytes * 4));
  }
  if (!fit.met || !have_low) return fit;
  double low_side = 1, high_side = 1;  // Illinois weights of the two ends' PSNR offsets
  int kept_end = 0;                    // +1: the low end moved last, -1: the high end
  for (int step = 0;
       step < 16 && double(fit.point.plane_bytes) > bracket_ratio * double(low.plane_bytes);
       ++step) {
    const double a = std::log(double(low.plane_bytes)), b = std::log(double(fit.point.plane_bytes));
    const double below = (psnr - low.psnr) * low_side, above = (fit.point.psnr - psnr) * high_side;
    const double t = std::clamp(below / std::max(below + above, 1e-12), 0.05, 0.95);
    const auto next = std::uint64_t(std::exp(a + t * (b - a)));
    if (next <= low.plane_bytes || next >= fit.point.plane_bytes) break;
    const bool reached = try_bytes(next);
    const int moved = reached ? -1 : +1;
    // The end that did not move twice running has its offset halved (Illinois).
    if (moved == kept_end)
      (reached ? low_side : high_side) *= 0.5;
    else
      low_side = high_side = 1;
    kept_end = moved;
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
                                const ContainerOptions& container, unsigned threads,
                                const PlanesFitStart& start) {
  PlanesCurve curve(field, global_basis_field(field, directions, terms), target, container,
                    threads);
  const std::uint64_t raw_bytes =
      2 * std::uint64_t(field.channels) * std::uint64_t(terms) * std::uint64_t(field.pixels());
  const double planes = double(field.channels) * terms;
  GlobalBasisFit fit =
      target.bytes > 0
          ? fit_bytes(curve, target.bytes, std::llround(start.overhead_per_plane * planes))
          : reach_psnr(curve, target.psnr, raw_bytes, start.plane_bytes);
  fit.points = curve.points();
  fit.learned.overhead_per_plane =
      (double(fit.point.bytes) - double(curve.fixed_bytes()) - double(fit.point.plane_bytes)) /
      planes;
  fit.learned.plane_bytes = fit.met ? fit.point.plane_bytes : start.plane_bytes;
  return fit;
}

}  // namespace relume
