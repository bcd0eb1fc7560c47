// Checkpoints of a long compression: the clustering state (bases, assignment, weights) and the
// iterations done, written atomically after every clustering iteration so that an interrupted run
// can continue (`relume compress --resume`). A fingerprint (the input and the settings that shape
// the clustering) is stored with it; resuming with a different one is refused.
#pragma once

#include <filesystem>
#include <string>

#include "compress/clustered_factorization.hpp"

namespace relume {

void write_checkpoint(const std::filesystem::path& path, const std::string& fingerprint,
                      const ClusterModel& model, const std::vector<IterationRecord>& iterations);

// Throws Error naming the file when it is unreadable, damaged or has another fingerprint.
ClusteringResume read_checkpoint(const std::filesystem::path& path, const std::string& fingerprint);

}  // namespace relume
