// Implementation of loading a field with progress.
#include "field/load_with_progress.hpp"

#include "core/progress.hpp"
#include "field/field_source.hpp"

namespace relume {

ReflectanceField load_field_with_progress(const std::string& input, FieldLoadOptions load) {
  const std::size_t images = describe_field(input).images.size();
  ProgressReporter progress("loading " + std::to_string(images) + " images", images);
  load.image_loaded = [&progress] { progress.advance(); };
  ReflectanceField field = load_field(input, load);
  progress.finish();
  return field;
}

}  // namespace relume
