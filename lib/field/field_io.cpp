// Loading reflectance fields from DiLiGenT-style folders and RTI .lp files; writing field folders.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <relume/error.hpp>
#include <relume/field.hpp>

#include "core/atomic_file.hpp"
#include "core/parallel.hpp"
#include "field/light_file.hpp"

namespace relume {
namespace fs = std::filesystem;

namespace {

struct FieldSource {
  std::vector<fs::path> images;
  LightDirections directions;
  LightRgb intensities;  // empty = all ones
  fs::path mask;         // empty = everything inside
};

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
      line.erase(line.find_last_not_of(" \t\r") + 1);
      if (!line.empty()) images.push_back(folder / line);
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
        if (!(source.intensities(i, c) > 0))
          throw Error((folder / "light_intensities.txt").string() + ": row " +
                      std::to_string(i + 1) + " has intensity " +
                      std::to_string(source.intensities(i, c)) + " (must be positive)");
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

int field_channels(int image_channels) { return image_channels >= 3 ? 3 : 1; }

// The intensity a channel of light i was divided by: its own for RGB, the mean for grey fields.
float channel_intensity(const ReflectanceField& field, int light, int channel) {
  return field.channels == 1 ? field.intensities.row(light).mean()
                             : field.intensities(light, channel);
}

void check_finite(const Image& image, const fs::path& path) {
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (std::isfinite(image.pixels[i])) continue;
    const std::size_t pixel = i / image.channels;
    throw Error("image " + path.string() + " has a non-finite value (" +
                std::to_string(image.pixels[i]) + ") at pixel (" +
                std::to_string(pixel % image.width) + ", " + std::to_string(pixel / image.width) +
                ") channel " + std::to_string(i % image.channels));
  }
}

}  // namespace

std::vector<std::uint8_t> load_mask(const fs::path& path, int width, int height) {
  const Image image = read_image(path);
  if (image.width != width || image.height != height)
    throw Error("mask " + path.string() + " is " + std::to_string(image.width) + "x" +
                std::to_string(image.height) + " but the images are " + std::to_string(width) +
                "x" + std::to_string(height));
  std::vector<std::uint8_t> mask(std::size_t(width) * height);
  for (std::size_t p = 0; p < mask.size(); ++p) {
    float any = 0;
    for (int c = 0; c < image.channels; ++c)
      any = std::max(any, image.pixels[p * image.channels + c]);
    mask[p] = any > 0 ? 1 : 0;
  }
  return mask;
}

ReflectanceField load_field(const fs::path& path, const FieldLoadOptions& options) {
  if (!fs::exists(path)) throw Error("reflectance field not found: " + path.string());
  const FieldSource source = fs::is_directory(path) ? describe_folder(path) : describe_lp(path);
  check_counts(source, path);

  const Image first = read_image(source.images.front(), options.image);
  ReflectanceField field;
  field.width = first.width;
  field.height = first.height;
  field.channels = field_channels(first.channels);
  const int lights = static_cast<int>(source.images.size());
  field.values.resize(field.pixels() * field.channels, lights);
  field.directions = source.directions;
  field.intensities = source.intensities.rows() ? source.intensities : LightRgb::Ones(lights, 3);
  for (const auto& image : source.images) field.image_names.push_back(image.filename().string());

  parallel_for(source.images.size(), options.threads, [&](std::size_t i, unsigned) {
    const Image image = i == 0 ? first : read_image(source.images[i], options.image);
    if (image.width != field.width || image.height != field.height)
      throw Error("image " + source.images[i].string() + " is " + std::to_string(image.width) +
                  "x" + std::to_string(image.height) + " but " + source.images[0].string() +
                  " is " + std::to_string(field.width) + "x" + std::to_string(field.height));
    if (image.channels != first.channels)
      throw Error("image " + source.images[i].string() + " has " + std::to_string(image.channels) +
                  " channels but " + source.images[0].string() + " has " +
                  std::to_string(first.channels));
    check_finite(image, source.images[i]);
    float scale[3];
    for (int c = 0; c < field.channels; ++c) scale[c] = 1.0f / channel_intensity(field, i, c);
    for (std::int64_t p = 0; p < field.pixels(); ++p)
      for (int c = 0; c < field.channels; ++c)
        field.values(p * field.channels + c, i) = image.pixels[p * image.channels + c] * scale[c];
  });

  field.mask = source.mask.empty() ? std::vector<std::uint8_t>(field.pixels(), 1)
                                   : load_mask(source.mask, field.width, field.height);
  if (first.source_bits > 0)
    field.noise_floor =
        float(1.0 / (std::ldexp(1.0, first.source_bits) - 1.0) / double(field.intensities.mean()));
  return field;
}

void write_field_folder(const fs::path& folder, const ReflectanceField& field) {
  fs::create_directories(folder);
  const int lights = field.lights();
  const int digits = std::max(3, static_cast<int>(std::to_string(lights).size()));
  std::vector<std::string> image_names(lights);
  for (int i = 0; i < lights; ++i) {
    const std::string number = std::to_string(i + 1);
    image_names[i] = std::string(digits - number.size(), '0') + number + ".exr";
  }
  parallel_for(lights, 0, [&](std::size_t i, unsigned) {
    Image image(field.width, field.height, field.channels);
    for (std::int64_t p = 0; p < field.pixels(); ++p)
      for (int c = 0; c < field.channels; ++c)
        image.pixels[p * field.channels + c] =
            field.values(p * field.channels + c, i) * channel_intensity(field, int(i), c);
    write_image(folder / image_names[i], image);
  });
  std::string names;
  for (const auto& name : image_names) names += name + "\n";
  write_rgb_rows(folder / "light_directions.txt", field.directions, "");
  write_rgb_rows(folder / "light_intensities.txt", field.intensities, "");
  Image mask(field.width, field.height, 1);
  for (std::size_t p = 0; p < field.mask.size(); ++p) mask.pixels[p] = field.mask[p] ? 1.0f : 0.0f;
  write_image(folder / "mask.png", mask);
  // The index goes last, so an interrupted write leaves no filenames.txt behind it.
  write_file_atomically(folder / "filenames.txt", names);
}

}  // namespace relume
