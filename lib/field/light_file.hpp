// Light-direction files in the conventions seen in the field:
//  - plain text, one `x y z` per row (DiLiGenT light_directions.txt); blank lines and # comments
//    are skipped;
//  - RTI .lp: first line N, then N lines `filename x y z` (decimal commas accepted, file names
//    may contain spaces: the last three fields are the direction);
//  - a field folder: its light_directions.txt, or its single .lp file.
// One tokenizer reads them all (core/text_numbers.hpp): fields are separated by any run of blanks
// (space, tab, \v, \f, \r) and numbers are parsed independently of the locale. Directions are
// normalised (without overflow for huge components); zero-length, non-numeric or non-finite ones,
// and light counts beyond an int, are refused with the file and line.
#pragma once

#include <filesystem>
#include <relume/field.hpp>
#include <string>
#include <vector>

namespace relume {

struct LpFile {
  std::vector<std::filesystem::path> images;  // as written in the file, relative to its folder
  LightDirections directions;
};

LpFile read_lp_file(const std::filesystem::path& path);

// Plain `x y z` rows (also used for `R G B` rows: see read_rgb_rows).
LightDirections read_direction_rows(const std::filesystem::path& path);

// Any of the three forms above.
LightDirections read_light_directions(const std::filesystem::path& path_or_folder);

// Rows of three finite numbers (light intensities, light vectors). `what` names the quantity in
// errors ("light intensity"). Negative values are allowed; NaN/Inf and values beyond float32 are
// refused.
LightRgb read_rgb_rows(const std::filesystem::path& path, const std::string& what);

// Writes rows of three numbers with full float precision, atomically.
void write_rgb_rows(const std::filesystem::path& path, const LightRgb& rows,
                    const std::string& header_comment);

}  // namespace relume
