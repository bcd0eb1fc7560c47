// Compressed fields a strip of pixel rows at a time, for fields larger than memory: a strip cut
// out of a whole compressed field (to measure it against the same strip of the original, read
// from disk), and strips stacked into a whole one (as compress builds it strip by strip).
#pragma once

#include <relume/compressed_field.hpp>

namespace relume {

// Pixel rows [first_row, first_row + rows) of `field` as a compressed field of their own: its
// function p is the field's function first_row x width x channels + p; bases and quantization
// are the field's, and so is the dark model when the strip has dark pixels (a field without dark
// pixels has none). Throws Error for rows outside the field.
CompressedField compressed_rows(const CompressedField& field, int first_row, int rows);

// Stacks `strip` below `field`'s rows (an empty field, height 0, becomes the strip); the first
// strip with dark pixels brings the dark model. Throws Error
// unless both have the same width, channels, lights, terms, clusters and transform.
void append_compressed_rows(CompressedField& field, const CompressedField& strip);

}  // namespace relume
