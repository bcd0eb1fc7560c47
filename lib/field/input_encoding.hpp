// How a field's 8-bit images are decoded, decided once per field from its first image and its
// folder (EightBitEncoding::automatic in relume/image.hpp):
//  - float images (EXR, HDR, float TIFF) and 16-bit images are linear (their values are used as
//    they are: 16-bit sources are sensor data, as DiLiGenT's are);
//  - 8-bit images of a DiLiGenT folder (one with light_intensities.txt) are linear: its crops
//    keep the top 8 bits of linear 16-bit sensor values;
//  - other 8-bit images (camera JPEGs, PNGs) are sRGB unless they declare a linear colour space.
// An explicit linear or srgb request is taken as it is.
#pragma once

#include <filesystem>
#include <relume/image.hpp>
#include <string>

#include "field/field_source.hpp"

namespace relume {

struct InputEncodingDecision {
  EightBitEncoding encoding = EightBitEncoding::linear;  // linear or srgb, never automatic
  std::string reason;  // for users: "8-bit jpeg, declared sRGB: decoded as sRGB"
};

InputEncodingDecision decide_input_encoding(const FieldSource& source, EightBitEncoding requested);

// The same for the field at `path` (a folder or an .lp file).
InputEncodingDecision decide_input_encoding(const std::filesystem::path& path,
                                            EightBitEncoding requested);

// "auto", "linear" or "srgb" (`--input-encoding`); throws Error naming another text.
EightBitEncoding parse_input_encoding(const std::string& text);

}  // namespace relume
