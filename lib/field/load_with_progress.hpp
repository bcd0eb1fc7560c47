// Loading a field with a progress bar over its images (core/progress.hpp): what the commands and
// the compression run show while a field loads.
#pragma once

#include <relume/field.hpp>
#include <string>

namespace relume {

// load_field(input, load) with one progress step per image read.
ReflectanceField load_field_with_progress(const std::string& input, FieldLoadOptions load);

}  // namespace relume
