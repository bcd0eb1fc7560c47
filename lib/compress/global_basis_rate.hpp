// The one-basis model (global_basis.hpp) fitted to a rate target: for a basis size, the weight
// planes' codestream is given the bytes the container has left (a byte target) or the fewest
// bytes whose PSNR reaches the target, to within 0.05 dB (regula falsi on the logarithm of the
// bytes). The rate targets (rate_control.hpp) try it at several basis sizes beside the clustered
// candidates.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <relume/container.hpp>
#include <vector>

#include "compress/rate_control.hpp"

namespace relume {

struct PlanesRatePoint {
  std::uint64_t plane_bytes = 0;  // the codestream
  std::uint64_t bytes = 0;        // the container
  double error = 0;               // Eq. 16 over the stored functions
  double psnr = 0;                // 8-bit, inside the target's region
};

// Where a fit starts, learned from the fit of another basis size: the container's bytes beyond
// its fixed sections and codestream, per plane (zstd shaves the codestream's per-plane markers;
// the header's digits vary), and for a PSNR target the codestream bytes that reached it and the
// PSNR's slope there (dB per e-fold of codestream bytes). Zero: nothing known.
struct PlanesFitStart {
  double overhead_per_plane = 0;
  std::uint64_t plane_bytes = 0;
  double psnr_slope = 0;
};

// Told of each point as it is measured (a few seconds each on a whole frame).
using PlanesPointHook = std::function<void(const PlanesRatePoint&)>;

// How far a byte target's fit goes: to a container within 1.5% under the bytes (`close`), or to
// its first container that fits (`first_fit`: within a few percent, one codestream where `close`
// may take two; enough to compare basis sizes, whose PSNR moves about 0.005 dB per 1% of bytes).
enum class BytesFit { close, first_fit };

struct GlobalBasisFit {
  CompressedField field;  // its weights coded at `point`
  PlanesRatePoint point;
  bool met = false;
  bool settled = true;                  // false: a first_fit that a close fit would go on from
  std::vector<PlanesRatePoint> points;  // every point measured, in order
  PlanesFitStart learned;               // where the fit of a neighbouring size may start
};

// The basis sizes a rate target may try for a field of `lights` lights, ascending: 4, 8, 16, 24,
// 32, 48, 64, 96, 128, 192, 256, ... up to the light count.
std::vector<int> global_basis_sizes(int lights);

// The gain in PSNR from `terms[2]` to `next` terms at the same bytes, predicted from the PSNRs
// of three sizes: the parabola through them against the logarithm of the size. On the 8-bit
// ball (0.2 to 2 B/px) it predicted the step from 64 to 96 terms within 0.04 dB from 32, 48 and
// 64; at 0.1 B/px -0.11 dB, where the step lost 0.5 dB.
double next_size_gain(const std::array<int, 3>& terms, const std::array<double, 3>& psnr, int next);

// The field with the first `terms` of `directions` (global_basis_directions; its basis stored
// for `noise_sigma`, as global_basis_field says) and its weight planes coded to meet `target`
// (exactly one of bytes and PSNR, as rate_control.hpp says) in a container written with
// `container`. Not met: the closest point (the fewest bytes for a byte target, the most for a PSNR
// target). `measured` hears of every point; `how_close` applies to byte targets.
GlobalBasisFit fit_global_basis(const ReflectanceField& field, const Eigen::MatrixXd& directions,
                                int terms, const std::vector<float>& noise_sigma,
                                const RateTarget& target, const ContainerOptions& container,
                                unsigned threads, const PlanesFitStart& start = {},
                                const PlanesPointHook& measured = {},
                                BytesFit how_close = BytesFit::close);

// `fitted`'s basis (a fit's field, its W as decoded) refitted to that W (refit_global_basis) and
// measured with `container`: kept when it meets `target` wherever `point` (the fit's) did and
// raises the PSNR, and `point` becomes its measure; else the basis goes back to what it was.
// Returns whether it was kept. On the ball at 0.05 to 0.1 B/px: +0.07 dB over the whole frame,
// +0.2 to 0.3 dB in the object, where the weights are coded hardest.
bool refit_fitted_basis(const ReflectanceField& original, CompressedField& fitted,
                        PlanesRatePoint& point, bool met, const RateTarget& target,
                        const ContainerOptions& container, unsigned threads);

}  // namespace relume
