// The files `relume eval` writes from an evaluation's numbers (eval/evaluation.hpp): the CSV
// tables, the per-pixel maps as NPY and the relit images as PNG; the JSON summary names them.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <relume/image.hpp>
#include <string>
#include <vector>

#include "eval/evaluation.hpp"

namespace relume {

// What write_eval_files wrote, as the summary names it.
struct EvalFiles {
  std::vector<std::string> csv, npy;
  std::string reference;  // the uncompressed field relit
  nlohmann::ordered_json relit,
      difference10;  // per method: its relit image, 10 |relit - reference|
};

// Writes into `directory` (which exists). Throws Error when a file cannot be written.
EvalFiles write_eval_files(const std::filesystem::path& directory, const EvaluationResult& result,
                           const ImageWriteOptions& images);

}  // namespace relume
