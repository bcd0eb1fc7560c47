// relume/compress.hpp: clustered sparse residual factorization of a reflectance field (Yamada,
// Peers, Debevec):
//   R[p,:] ~ W[p,:] F^{c(p)} + E[p,:]
// The functions a scene needs (inside the mask, not all zero; each colour channel its own
// function) are clustered by L1 factorization (IRLS fits; the reassignment fits run on an OpenCL
// device or in C++), and each keeps its largest residual entries. The result is what
// relume/container.hpp stores and relume/relight.hpp relights. The `relume compress` command
// offers more (a target error, checkpoints and resume, exact LP refits, reports).
#pragma once

#include <cstdint>
#include <relume/compressed_field.hpp>
#include <relume/field.hpp>
#include <string>

namespace relume {

struct CompressOptions {
  int clusters = 64;  // K
  int terms = 4;      // t, basis functions per cluster (1 to 16)
  // Residual entries kept per function: `residual_entries` when >= 0, else residual_percent of
  // the lights.
  int residual_entries = -1;
  double residual_percent = 5.0;
  float residual_threshold = 0.0f;  // entries with |value| <= this (field units) are dropped
  BasisTransform transform = BasisTransform::identity;
  int multires_levels = 0;  // cluster a field downsampled 2x per level first
  int iterations = 4;       // cap on L1 iterations (F-step + reassignment)
  std::uint64_t seed = 1;   // of the cluster seeding
  unsigned threads = 0;     // 0 = all cores
  // Reassignment fits on this OpenCL device (see RelighterOptions::device); false: the C++ path.
  bool opencl_assignment = true;
  std::string device;
  bool quiet = true;  // no progress lines on stderr
};

// Throws Error for options out of range or a field with nothing to store.
CompressedField compress(const ReflectanceField& field, const CompressOptions& options = {});

}  // namespace relume
