// Implementation of strip-by-strip field reading (see field_strips.hpp).
#include "field/field_strips.hpp"

#include <sys/resource.h>

#include <relume/error.hpp>
#include <string>

#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "field/field_source.hpp"
#include "field/input_encoding.hpp"
#include "field/light_image_rows.hpp"
#include "field/mask_file.hpp"

namespace relume {
namespace fs = std::filesystem;

namespace {

// Raises the soft open-file limit toward the hard one so that `files` more fit; throws Error with
// the numbers when they cannot.
void make_room_for_open_files(std::size_t files) {
  constexpr rlim_t margin = 64;  // the process's own files, OpenCL's, the outputs'
  rlimit limit{};
  if (getrlimit(RLIMIT_NOFILE, &limit) != 0) return;
  const rlim_t needed = rlim_t(files) + margin;
  if (limit.rlim_cur != RLIM_INFINITY && limit.rlim_cur < needed) {
    limit.rlim_cur = limit.rlim_max == RLIM_INFINITY ? needed : std::min(needed, limit.rlim_max);
    setrlimit(RLIMIT_NOFILE, &limit);
    getrlimit(RLIMIT_NOFILE, &limit);
  }
  if (limit.rlim_cur != RLIM_INFINITY && limit.rlim_cur < needed)
    throw Error("reading " + std::to_string(files) +
                " light images in strips keeps them all open, but the open-file limit is " +
                std::to_string(limit.rlim_cur) + " (ulimit -n; the hard limit is " +
                std::to_string(limit.rlim_max) + ")");
}

}  // namespace

FieldStripReader::FieldStripReader(const fs::path& path, const FieldLoadOptions& options)
    : path_(path), threads_(options.threads) {
  const FieldSource source = describe_field(path);
  if (options.use_mask && !options.mask_file.empty() && !fs::exists(options.mask_file))
    throw Error("mask not found: " + options.mask_file.string());
  images_ = source.images;
  read_options_.eight_bit = decide_input_encoding(source, options.image.eight_bit).encoding;
  make_room_for_open_files(images_.size());
  open_images();
  const ImageRowReader& first = readers_.front();
  header_.width = first.width();
  header_.height = first.height();
  header_.channels = field_channels(first.channels());
  const int lights = int(images_.size());
  header_.values.resize(0, lights);
  header_.directions = source.directions;
  header_.intensities = source.intensities.rows() ? source.intensities : LightRgb::Ones(lights, 3);
  for (const auto& image : images_) header_.image_names.push_back(image.filename().string());
  const fs::path mask = options.mask_file.empty() ? source.mask : options.mask_file;
  header_.mask = mask.empty() || !options.use_mask ? std::vector<std::uint8_t>(header_.pixels(), 1)
                                                   : read_mask(mask, header_.width, header_.height);
  header_.noise_floor =
      integer_noise_floor(first.source_bits(), read_options_.eight_bit, header_.intensities);
}

void FieldStripReader::open_images() {
  readers_.clear();
  readers_.reserve(images_.size());
  for (const fs::path& image : images_) {
    readers_.emplace_back(image, read_options_);
    check_same_shape(readers_.back(), readers_.front());
  }
  next_row_ = 0;
}

void FieldStripReader::rewind() { open_images(); }

ReflectanceField FieldStripReader::read(int first_row, int rows) {
  if (first_row < next_row_ || rows < 1 || first_row + rows > header_.height)
    throw Error("field " + path_.string() + ": strip of rows " + std::to_string(first_row) +
                " to " + std::to_string(first_row + rows) + " is out of order or outside its " +
                std::to_string(header_.height) + " rows");
  ReflectanceField strip;
  strip.width = header_.width;
  strip.height = rows;
  strip.channels = header_.channels;
  strip.directions = header_.directions;
  strip.intensities = header_.intensities;
  strip.image_names = header_.image_names;
  strip.noise_floor = header_.noise_floor;
  const std::size_t first_pixel = std::size_t(first_row) * header_.width;
  strip.mask.assign(header_.mask.begin() + std::ptrdiff_t(first_pixel),
                    header_.mask.begin() + std::ptrdiff_t(first_pixel + strip.pixels()));
  const int lights = header_.lights();
  check_memory_need(std::uint64_t(strip.pixels()) * strip.channels * lights * sizeof(float),
                    "a strip of " + std::to_string(rows) + " rows of " + path_.string());
  strip.values.resize(strip.pixels() * strip.channels, lights);
  parallel_for(readers_.size(), threads_, [&](std::size_t i, unsigned) {
    ImageRowReader& image = readers_[i];
    // Rows skipped since the last strip: OpenImageIO seeks (EXR, TIFF) or reads past them (PNG,
    // JPEG, which decode forward).
    std::vector<float> pixels(std::size_t(strip.pixels()) * image.channels());
    image.read_rows(first_row, rows, pixels.data());
    store_light_rows(strip, int(i), pixels.data(), image.channels(), first_row, images_[i]);
  });
  next_row_ = first_row + rows;
  return strip;
}

void append_field_rows(ReflectanceField& field, const ReflectanceField& strip, int first_row,
                       int rows) {
  if (first_row < 0 || rows < 0 || first_row + rows > strip.height)
    throw Error("rows " + std::to_string(first_row) + " to " + std::to_string(first_row + rows) +
                " are outside the strip's " + std::to_string(strip.height));
  if (field.height == 0) {
    field.width = strip.width;
    field.channels = strip.channels;
    field.directions = strip.directions;
    field.intensities = strip.intensities;
    field.image_names = strip.image_names;
    field.noise_floor = strip.noise_floor;
    field.values.resize(0, strip.lights());
    field.mask.clear();
  } else if (strip.width != field.width || strip.channels != field.channels ||
             strip.lights() != field.lights()) {
    throw Error("cannot stack field strips of different shapes");
  }
  const Eigen::Index row_functions = Eigen::Index(strip.width) * strip.channels;
  const Eigen::Index old_rows = field.values.rows();
  field.values.conservativeResize(old_rows + rows * row_functions, Eigen::NoChange);
  field.values.bottomRows(rows * row_functions) =
      strip.values.middleRows(first_row * row_functions, rows * row_functions);
  const auto mask_begin = strip.mask.begin() + std::ptrdiff_t(first_row) * strip.width;
  field.mask.insert(field.mask.end(), mask_begin, mask_begin + std::ptrdiff_t(rows) * strip.width);
  field.height += rows;
}

}  // namespace relume
