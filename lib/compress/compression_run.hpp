// One compression run, the driver behind every front (relume/compress.hpp: compress_file,
// compress_with_report, compress; `relume compress`; Python's relume.compress): the plan (in
// memory, or streamed in strips within the memory budget, over MPI ranks when there are several),
// checkpoints after every clustering iteration and resume, the target searches, the storage
// precision, the container, the error measures and the JSON report.
#pragma once

#include <filesystem>
#include <memory>
#include <relume/compress.hpp>
#include <string>

#include "compress/opencl_assignment.hpp"

namespace relume {

// Where one run's reassignment fits run, set up once for several runs (the inputs of one
// command): the OpenCL assigner that options.assign and options.device ask for (it notes the
// device), or none for the C++ path and for clustered PCA.
std::unique_ptr<OpenClAssigner> assigner_for(const CompressOptions& options);

// compress_file with an assigner made by assigner_for (null: the C++ path). Under MPI every rank
// calls it; the root writes the container and gets the report, the other ranks an empty one.
CompressionReport compress_file_with(const std::string& input, const std::filesystem::path& output,
                                     const CompressOptions& options, OpenClAssigner* assigner);

}  // namespace relume
