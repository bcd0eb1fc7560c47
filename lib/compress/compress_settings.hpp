// The public CompressOptions (relume/compress.hpp) made into the settings the compression stages
// take, checked once, before any work: every name and number is validated here and an Error names
// the option (as `relume compress` spells it) and the bad value. One mapping for every front.
#pragma once

#include <relume/compress.hpp>

#include "compress/clustered_factorization.hpp"
#include "compress/compression_plan.hpp"
#include "compress/storage_precision.hpp"

namespace relume {

struct CompressSettings {
  CompressionOptions compression;  // the clustering, the residual and the method
  StoragePrecision precision;      // how the result is stored
  std::string solver;              // "irls" or the exact refit's solver, for the records
};

// Throws Error naming the first bad option.
CompressSettings compress_settings(const CompressOptions& options);

// A rate target (bytes, bytes per pixel or PSNR) is set.
bool has_rate_target(const CompressOptions& options);

// Throws Error naming the options a streamed compression cannot honour (the targets, a term
// budget, and what check_streamable_options names).
void check_streamable(const CompressOptions& options, const CompressionOptions& compression);

// The settings that shape the clustering, with the input: a checkpoint is only resumed when its
// fingerprint is the same.
std::string checkpoint_fingerprint(const std::string& input, const CompressOptions& options,
                                   const CompressionOptions& compression);

}  // namespace relume
