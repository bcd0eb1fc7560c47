// Implementation of the one-basis model's rate fitting (see global_basis_rate.hpp).
#include "compress/global_basis_rate.hpp"

#include <algorithm>
#include <cmath>

#include "compress/global_basis.hpp"
#include "container/container.hpp"
#include "container/weight_plane_coding.hpp"
#include "core/interruption.hpp"
#include "model/weight_planes.hpp"

namespace relume {
namespace {

// The fewest codestream bytes tried: below this the planes are a few DC values.
constexpr std::uint64_t min_plane_bytes = 512;
// A PSNR target's search stops when its two ends are this close in bytes, or when a point
// reaches the target by at most psnr_tolerance dB (rate targets promise 0.1 dB).
constexpr double bracket_ratio = 1.005;
constexpr double psnr_tolerance = 0.05;
// encode_jpeg2000_planes lands up to this factor under the bytes it is given.
constexpr double coder_resolution = 1.01;

// The one-basis field's points at one basis size: its weight planes quantized once, coded at each
// size asked into one working field, and the point a fit keeps swapped into a second, so that a
// point costs no copy of W.
class PlanesCurve {
 public:
  PlanesCurve(const ReflectanceField& original, CompressedField base, const RateTarget& target,
              const ContainerOptions& container, unsigned threads, const PlanesPointHook& measured)
      : original_(original),
        target_(target),
        container_(container),
        threads_(threads),
        measured_(measured),
        quantized_(quantize_weight_planes(base)),
        work_(std::move(base)) {
    // The container's bytes besides the codestream: those of a one-byte stand-in, less that byte.
    work_.coded_weights.codestream = {0};
    work_.coded_weights.step = 1.0f;
    fixed_bytes_ = plan_container(work_, container_).file_bytes - 1;
  }

  std::uint64_t fixed_bytes() const { return fixed_bytes_; }

  // The field with its planes coded in at most `plane_bytes`, measured; keep() keeps it.
  // A safe point for SIGINT / SIGTERM before each coding (a few seconds each on a whole frame).
  PlanesRatePoint measure(std::uint64_t plane_bytes) {
    throw_if_interrupted();
    code_quantized_planes(work_, quantized_, plane_bytes, threads_);
    PlanesRatePoint point;
    point.plane_bytes = work_.coded_weights.codestream.size();
    const StoredMeasure stored = measure_stored(original_, work_, target_, container_, threads_);
    point.bytes = stored.bytes;
    point.error = stored.error;
    point.psnr = stored.psnr;
    points_.push_back(point);
    if (measured_) measured_(point);
    return point;
  }

  // The field of the last point measured becomes the one take_best() gives.
  void keep() {
    if (kept_)
      std::swap(work_, best_);
    else
      best_ = work_;
    kept_ = true;
  }

  CompressedField take_best() { return std::move(best_); }

  const std::vector<PlanesRatePoint>& points() const { return points_; }

 private:
  const ReflectanceField& original_;
  const RateTarget& target_;
  const ContainerOptions& container_;
  unsigned threads_;
  const PlanesPointHook& measured_;
  QuantizedWeightPlanes quantized_;
  CompressedField work_, best_;
  bool kept_ = false;
  std::uint64_t fixed_bytes_ = 0;
  std::vector<PlanesRatePoint> points_;
};

// A codestream whose container fits `bytes` and comes within 1.5% of them: aimed at 99.3% of the
// bytes (clear of both ends) after the fixed sections and the overhead learned from another
// size, then corrected by what the container came to (zstd shaves the codestream's markers, the
// header's step has more or fewer digits), keeping the largest that fits. `first_fit`: stops at
// the first that fits, `settled` saying whether it came within the 1.5%.
GlobalBasisFit fit_bytes(PlanesCurve& curve, std::uint64_t bytes, std::int64_t overhead,
                         BytesFit how_close) {
  constexpr double aim_share = 0.993, enough_share = 0.985;
  const double aim = aim_share * double(bytes);
  GlobalBasisFit fit;
  std::int64_t plane_bytes = std::llround(aim) - std::int64_t(curve.fixed_bytes()) - overhead;
  for (int attempt = 0; attempt < 4; ++attempt) {
    plane_bytes = std::max<std::int64_t>(plane_bytes, min_plane_bytes);
    const PlanesRatePoint point = curve.measure(std::uint64_t(plane_bytes));
    const bool met = point.bytes <= bytes;
    // The first point, a fit where there was none, or a larger fit.
    if (attempt == 0 || (met && (!fit.met || point.bytes > fit.point.bytes)) ||
        (!met && !fit.met && point.bytes < fit.point.bytes)) {
      curve.keep();
      fit.point = point;
      fit.met = met;
    }
    const bool close = met && double(point.bytes) >= enough_share * double(bytes);
    if (close || (!met && plane_bytes == std::int64_t(min_plane_bytes))) break;
    if (met && how_close == BytesFit::first_fit) {
      fit.settled = false;
      break;
    }
    plane_bytes += std::llround(aim - double(point.bytes));
  }
  return fit;
}

// The PSNR's slope in dB per e-fold of codestream bytes between two points; 0 when they are too
// close in bytes to say or the PSNR does not rise.
double psnr_slope(const PlanesRatePoint& a, const PlanesRatePoint& b) {
  const double run = std::log(double(b.plane_bytes) / double(a.plane_bytes));
  if (std::abs(run) < 0.01) return 0;
  const double slope = (b.psnr - a.psnr) / run;
  return slope > 0 ? slope : 0;
}

// The fewest codestream bytes whose PSNR reaches `psnr`, between min_plane_bytes and the planes'
// raw 16-bit size. From `start`'s bytes (another size's answer), else a 64th of the raw size, the
// search first brackets the target: each step moves the logarithm of the bytes by the PSNR still
// missing over the slope (of the last two points, else `start`'s, else 1 dB per e-fold), a
// quarter further so as to cross, at most a factor of 16. Then regula falsi on the logarithm of
// the bytes (in which the PSNR is nearly straight), with the Illinois halving so neither end
// sticks. It stops when a point reaches the target by at most psnr_tolerance, when the ends are
// within bracket_ratio, or when the coder returns a codestream already measured.
GlobalBasisFit reach_psnr(PlanesCurve& curve, double psnr, std::uint64_t raw_bytes,
                          const PlanesFitStart& start) {
  raw_bytes = std::max(raw_bytes, 2 * min_plane_bytes);
  GlobalBasisFit fit;   // the fewest bytes that reached it
  PlanesRatePoint low;  // the most bytes known not to reach it
  bool have_low = false, repeated = false;
  std::vector<PlanesRatePoint> seen;
  const auto try_bytes = [&](std::uint64_t plane_bytes) {
    const PlanesRatePoint point = curve.measure(plane_bytes);
    repeated = std::any_of(seen.begin(), seen.end(), [&](const PlanesRatePoint& other) {
      return other.plane_bytes == point.plane_bytes;
    });
    seen.push_back(point);
    const auto keep = [&](bool met) {
      curve.keep();
      fit.point = point;
      fit.met = met;
    };
    if (point.psnr >= psnr) {
      if (!fit.met || point.plane_bytes < fit.point.plane_bytes) keep(true);
    } else if (!have_low || point.plane_bytes > low.plane_bytes) {
      low = point;
      have_low = true;
      if (!fit.met) keep(false);
    }
  };
  const auto close_enough = [&] {
    return repeated || (fit.met && fit.point.psnr - psnr <= psnr_tolerance);
  };
  std::uint64_t bytes = std::clamp(start.plane_bytes ? start.plane_bytes : raw_bytes / 64,
                                   min_plane_bytes, raw_bytes);
  try_bytes(bytes);
  while (!(fit.met && have_low) && !close_enough()) {
    const PlanesRatePoint& last = seen.back();
    double slope = seen.size() >= 2 ? psnr_slope(seen[seen.size() - 2], last) : 0;
    if (slope == 0) slope = start.psnr_slope > 0 ? start.psnr_slope : 1.0;
    const double step =
        std::clamp(1.25 * (psnr - last.psnr) / slope, -std::log(16.0), std::log(16.0));
    const auto next = std::uint64_t(std::clamp(double(last.plane_bytes) * std::exp(step),
                                               double(min_plane_bytes), double(raw_bytes)));
    if (next == last.plane_bytes) break;  // at an end of the range
    try_bytes(bytes = next);
  }
  if (!fit.met || !have_low) return fit;
  double low_side = 1, high_side = 1;  // Illinois weights of the two ends' PSNR offsets
  int kept_end = 0;                    // +1: the low end moved last, -1: the high end
  for (int step = 0; step < 16 && !close_enough() &&
                     double(fit.point.plane_bytes) > bracket_ratio * double(low.plane_bytes);
       ++step) {
    const double a = std::log(double(low.plane_bytes)), b = std::log(double(fit.point.plane_bytes));
    const double below = (psnr - low.psnr) * low_side, above = (fit.point.psnr - psnr) * high_side;
    const double t = std::clamp(below / std::max(below + above, 1e-12), 0.05, 0.95);
    // The coder lands up to 1% under the bytes asked: closer to the low end is the low end.
    const auto next =
        std::max(std::uint64_t(std::exp(a + t * (b - a))),
                 std::uint64_t(std::ceil(coder_resolution * double(low.plane_bytes))));
    if (next >= fit.point.plane_bytes) break;
    try_bytes(next);
    const bool reached = seen.back().psnr >= psnr;
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

double next_size_gain(const std::array<int, 3>& terms, const std::array<double, 3>& psnr,
                      int next) {
  const double at = std::log(double(next));
  double value = 0;  // Lagrange's form of the parabola, at `next`
  for (std::size_t i = 0; i < 3; ++i) {
    double weight = 1;
    for (std::size_t j = 0; j < 3; ++j)
      if (j != i)
        weight *= (at - std::log(double(terms[j]))) /
                  (std::log(double(terms[i])) - std::log(double(terms[j])));
    value += weight * psnr[i];
  }
  return value - psnr[2];
}

GlobalBasisFit fit_global_basis(const ReflectanceField& field, const Eigen::MatrixXd& directions,
                                int terms, const std::vector<float>& noise_sigma,
                                const RateTarget& target, const ContainerOptions& container,
                                unsigned threads, const PlanesFitStart& start,
                                const PlanesPointHook& measured, BytesFit how_close) {
  CompressedField fitted = global_basis_field(field, directions, terms, threads, noise_sigma);
  fitted.coded_weights.colour_angles = principal_colour_angles(fitted);
  PlanesCurve curve(field, std::move(fitted), target, container, threads, measured);
  const std::uint64_t raw_bytes =
      2 * std::uint64_t(field.channels) * std::uint64_t(terms) * std::uint64_t(field.pixels());
  const double planes = double(field.channels) * terms;
  GlobalBasisFit fit = target.bytes > 0
                           ? fit_bytes(curve, target.bytes,
                                       std::llround(start.overhead_per_plane * planes), how_close)
                           : reach_psnr(curve, target.psnr, raw_bytes, start);
  fit.field = curve.take_best();
  fit.points = curve.points();
  fit.learned.overhead_per_plane =
      (double(fit.point.bytes) - double(curve.fixed_bytes()) - double(fit.point.plane_bytes)) /
      planes;
  fit.learned.plane_bytes = fit.met ? fit.point.plane_bytes : start.plane_bytes;
  fit.learned.psnr_slope = start.psnr_slope;
  // The slope near the target: of the two points measured closest to its PSNR.
  std::vector<PlanesRatePoint> nearest = fit.points;
  std::sort(nearest.begin(), nearest.end(), [&](const auto& a, const auto& b) {
    return std::abs(a.psnr - target.psnr) < std::abs(b.psnr - target.psnr);
  });
  for (std::size_t i = 1; target.psnr > 0 && i < nearest.size(); ++i)
    if (const double slope = psnr_slope(nearest[0], nearest[i]); slope > 0) {
      fit.learned.psnr_slope = slope;
      break;
    }
  return fit;
}

bool refit_fitted_basis(const ReflectanceField& original, CompressedField& fitted,
                        PlanesRatePoint& point, bool met, const RateTarget& target,
                        const ContainerOptions& container, unsigned threads) {
  throw_if_interrupted();
  const std::vector<float> bases = fitted.bases;
  const std::vector<float> scales = fitted.quantization.basis_scales;
  refit_global_basis(original, fitted, threads);
  const StoredMeasure refit = measure_stored(original, fitted, target, container, threads);
  const bool refit_met = target.bytes > 0 ? refit.bytes <= target.bytes : refit.psnr >= target.psnr;
  if ((refit_met || !met) && refit.psnr > point.psnr) {
    point.bytes = refit.bytes;
    point.error = refit.error;
    point.psnr = refit.psnr;
    return true;
  }
  fitted.bases = bases;
  fitted.quantization.basis_scales = scales;
  return false;
}

}  // namespace relume
