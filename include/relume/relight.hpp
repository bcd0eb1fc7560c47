// relume/relight.hpp: relighting a compressed field under a light vector (one RGB row per light,
// from relume/lighting.hpp or a file), on an OpenCL device or with the CPU reference, and the
// reference relighting of an uncompressed field.
//
// The CPU reference accumulates in double: the ground truth that the OpenCL kernels are tested
// against. For stored row s (function p, channel c = p % channels, cluster k):
//   v[k][j][c] = sum_i F^k[j][i] * I[i][c]
//   out[p]     = sum_j W[s][j] * v[k][j][c] + sum_{e < min(nnz_s, cap)} E[s][e] * I[light(e)][c]
// Functions that are not stored relight to 0. A residual cap below a row's length uses its
// largest entries only (the dynamic residual): faster and less accurate.
#pragma once

#include <cstdint>
#include <memory>
#include <relume/compressed_field.hpp>
#include <relume/field.hpp>
#include <relume/image.hpp>
#include <string>
#include <vector>

namespace relume {

// Which parts of the sum to evaluate: the whole relit image, or only the residual term E . I
// (the residual SpMV on its own).
enum class RelightTerms { all, residual_only };

// The reference relighter of one field: checks the field once (check_relightable), then relights
// it for any number of light vectors. Keeps a reference to the field, which must outlive it.
class CompressedRelightReference {
 public:
  explicit CompressedRelightReference(const CompressedField& field);

  // Relit image (width x height x channels); at most residual_cap >= 0 entries per row are used
  // (all_residual_entries: every entry).
  Image relight(const LightRgb& light, int residual_cap = all_residual_entries,
                RelightTerms terms = RelightTerms::all, unsigned threads = 0) const;

 private:
  const CompressedField& field_;
};

// One-off form of CompressedRelightReference(field).relight(...).
Image relight_compressed_reference(const CompressedField& field, const LightRgb& light,
                                   int residual_cap = all_residual_entries,
                                   RelightTerms terms = RelightTerms::all, unsigned threads = 0);

// Reference relighting of an uncompressed field: out[p] = sum_i R[p,i] * I[i, c(p)], accumulated
// in double. `light_vector` has one RGB row per light; a grey field uses the mean of each row.
Image relight_field(const ReflectanceField& field, const LightRgb& light_vector,
                    unsigned threads = 0);

struct RelighterOptions {
  // OpenCL device: a substring of "platform / device" (see `relume devices`); empty: the
  // RELUME_DEVICE environment variable, else the first GPU, else PoCL's CPU device.
  std::string device;
  bool cpu_reference = false;  // relight with CompressedRelightReference instead of OpenCL
  // Keep negative values of a relit image. By default, a field compressed from non-negative data
  // (CompressedField::non_negative) relit under a light vector with no negative entry has its
  // negative values (the fit's undershoot) set to 0: the true image is non-negative there, so
  // this moves no value away from it. Signed light vectors are never projected.
  bool allow_negative = false;
};

// Relights one compressed field many times. The OpenCL path uploads the field once (in the
// kernels' layout) and relights a batch of light vectors in one pass over W and E; it keeps no
// reference to `field`. With cpu_reference the field must outlive the relighter. Throws Error for
// an inconsistent field or when no OpenCL device matches.
class Relighter {
 public:
  explicit Relighter(const CompressedField& field, const RelighterOptions& options = {});
  ~Relighter();
  Relighter(const Relighter&) = delete;
  Relighter& operator=(const Relighter&) = delete;

  // One image (width x height x channels); at most residual_cap >= 0 entries per row are used
  // (all_residual_entries: every entry).
  Image relight(const LightRgb& light, int residual_cap = all_residual_entries);
  // One image per light vector.
  std::vector<Image> relight_batch(const std::vector<LightRgb>& lights,
                                   int residual_cap = all_residual_entries);

  // "platform / device" of the OpenCL device, or "CPU reference (C++)".
  std::string device_name() const;
  // Negative values set to 0 in the last call's images (see RelighterOptions::allow_negative).
  std::uint64_t last_projected_values() const;
  // Bytes and device seconds of the kernels of the last call (0 for the CPU reference).
  double last_kernel_bytes() const;
  double last_kernel_seconds() const;

 private:
  struct Backend;
  std::unique_ptr<Backend> backend_;
};

}  // namespace relume
