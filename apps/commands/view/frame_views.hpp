// The viewer's other views of a frame. The error view shows where a residual cap departs from the
// full residual: |capped - full| per pixel, in false colour for the page (black where the two
// agree exactly, then a log scale from 1e-4 (dark blue) through 1e-2 (red) to 1e-1 (yellow) and
// beyond (white) of the full frame's bright level, the 99th percentile of the lit object's
// luminance as --exposure auto measures it), and as the plain per-channel absolute difference in
// linear floats for EXR. The mask view shows which pixels the container stores: white where it
// stores functions, blue where its dark model relights them, dark red inside the mask with nothing
// stored (all-zero functions), black outside the mask.
#pragma once

#include <relume/compressed_field.hpp>
#include <relume/image.hpp>

namespace relume {

// The false-colour error view (3 channels, linear values that PNG/JPEG encode with exposure 0 as
// the colours above). `image` and `reference` have the same size; `mask` as the field's.
Image false_colour_error(const Image& image, const Image& reference,
                         const std::vector<std::uint8_t>& mask);

// |image - reference| per value (the EXR error view).
Image absolute_difference(const Image& image, const Image& reference);

// The mask view (3 channels) of the field's pixels.
Image stored_pixels_view(const CompressedField& field);

}  // namespace relume
