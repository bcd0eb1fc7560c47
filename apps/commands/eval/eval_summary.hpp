// The JSON summary of `relume eval` (eval.json): the field, the settings as run, the function
// classes, the headline comparison of every configuration, the per-pixel map's count, the
// relighting device, the images and every file written.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands/eval/eval_files.hpp"

namespace relume {

// `input`: the field as named on the command line; `environment`: the relighting's map by name;
// `plots`: the plots drawn; `seconds`: the whole command's.
nlohmann::ordered_json eval_summary(const std::string& input, const ReflectanceField& field,
                                    const std::string& environment, const EvaluationResult& result,
                                    const EvalFiles& files, const std::vector<std::string>& plots,
                                    double seconds);

}  // namespace relume
