// Finding a field's images, light directions, intensities and mask.
#include "field/field_source.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <relume/error.hpp>

#include "core/text_numbers.hpp"
#include "field/light_file.hpp"

namespace relume {
namespace fs = std::filesystem;

namespace {

bool is_image_file(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  for (const char* known : {".png", ".exr", ".hdr", ".tif", ".tiff", ".jpg", ".jpeg", ".pfm"})
    if (ext == known) return true;
  return false;
}

bool is_numbered(const fs::path& path) {
  const std::string stem = path.stem().string();
  return !stem.empty() && std::all_of(stem.begin(), stem.end(), ::isdigit);
}

// Orders numbered images by their number (2.png before 10.png), equal numbers by name.
bool numbered_before(const fs::path& a, const fs::path& b) {
  const auto number = [](const fs::path& path) {
    const std::string stem = path.stem().string();
    return stem.substr(std::min(stem.find_first_not_of('0'), stem.size()));
  };
  const std::string x = number(a), y = number(b);
  if (x.size() != y.size()) return x.size() < y.size();
  return x != y ? x < y : a < b;
}

std::vector<fs::path> read_filenames(const fs::path& folder) {
  const fs::path list = folder / "filenames.txt";
  std::vector<fs::path> images;
  if (fs::exists(list)) {
    std::ifstream in(list);
    for (std::string line; std::getline(in, line);) {
      const std::string_view name = trim_blanks(line);
      if (!name.empty()) images.push_back(folder / std::string(name));
    }
    if (images.empty()) throw Error(list.string() + " names no images");
    return images;
  }
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.is_regular_file() && is_image_file(entry.path()) && is_numbered(entry.path()))
      images.push_back(entry.path());
  // By number: row i of light_directions.txt belongs to the i-th image.
  std::sort(images.begin(), images.end(), numbered_before);
  if (images.empty())
    throw Error("folder " + folder.string() +
                " has no filenames.txt and no numbered images (001.png, ...)");
  return images;
}

FieldSource describe_lp(const fs::path& lp_path) {
  LpFile lp = read_lp_file(lp_path);
  FieldSource source;
  for (const auto& name : lp.images) source.images.push_back(lp_path.parent_path() / name);
  source.directions = std::move(lp.directions);
  return source;
}

FieldSource describe_folder(const fs::path& folder) {
  if (!fs::exists(folder / "light_directions.txt")) {
    std::vector<fs::path> lp_files;
    for (const auto& entry : fs::directory_iterator(folder))
      if (entry.path().extension() == ".lp") lp_files.push_back(entry.path());
    if (lp_files.size() == 1) return describe_lp(lp_files.front());
    throw Error(
        "folder " + folder.string() +
        " is not a reflectance field: it has no light_directions.txt and no single .lp file");
  }
  FieldSource source;
  source.images = read_filenames(folder);
  source.directions = read_direction_rows(folder / "light_directions.txt");
  if (fs::exists(folder / "light_intensities.txt")) {
    source.intensities = read_rgb_rows(folder / "light_intensities.txt", "light intensity");
    for (Eigen::Index i = 0; i < source.intensities.rows(); ++i)
      for (int c = 0; c < 3; ++c)
        if (!(source.intensities(i, c) > 0) || !std::isfinite(1.0f / source.intensities(i, c)))
          throw Error(
              (folder / "light_intensities.txt").string() + ": row " + std::to_string(i + 1) +
              " has intensity " + std::to_string(source.intensities(i, c)) +
              " (must be positive, and at least 3e-39 so that images can be divided by it)");
  }
  if (fs::exists(folder / "mask.png")) source.mask = folder / "mask.png";
  return source;
}

void check_counts(const FieldSource& source, const fs::path& path) {
  const auto images = static_cast<Eigen::Index>(source.images.size());
  if (source.directions.rows() != images)
    throw Error(path.string() + ": " + std::to_string(source.directions.rows()) +
                " light directions but " + std::to_string(images) + " images");
  if (source.intensities.rows() != 0 && source.intensities.rows() != images)
    throw Error(path.string() + ": " + std::to_string(source.intensities.rows()) +
                " light intensities but " + std::to_string(images) + " images");
}

}  // namespace

FieldSource describe_field(const fs::path& path) {
  if (!fs::exists(path)) throw Error("reflectance field not found: " + path.string());
  // Anything else is read as an .lp file, which showed an image's first bytes as its light count.
  if (!fs::is_directory(path) && is_image_file(path)) {
    const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    throw Error(path.string() +
                " is an image, not a reflectance field: give the folder of the light images "
                "(DiLiGenT's layout, with light_directions.txt: " +
                folder.string() + " if that is it) or an RTI .lp file that lists them");
  }
  const FieldSource source = fs::is_directory(path) ? describe_folder(path) : describe_lp(path);
  check_counts(source, path);
  return source;
}

}  // namespace relume
