// Fuzz target: the field folder loader's text files. The input is split at the first two bytes
// 0x00 into filenames.txt, light_directions.txt and light_intensities.txt of a folder that also
// holds a 2x2 image 001.png; load_field then reads the lists, the lights and the images they name.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <relume/field.hpp>
#include <relume/image.hpp>
#include <string_view>

#include "fuzz_support.hpp"

namespace {

const std::filesystem::path& field_folder() {
  static const std::filesystem::path folder = [] {
    const auto path = relume::fuzz::scratch_folder() / "field";
    std::filesystem::create_directories(path);
    relume::Image image(2, 2, 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i) / 12;
    relume::write_image(path / "001.png", image);
    return path;
  }();
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const char* names[] = {"filenames.txt", "light_directions.txt", "light_intensities.txt"};
  std::size_t start = 0;
  for (int part = 0; part < 3; ++part) {
    const std::size_t end = part < 2 ? std::min(input.find('\0', start), size) : size;
    const std::string_view text = start <= size ? input.substr(start, end - start) : "";
    relume::fuzz::write_scratch_file("field/" + std::string(names[part]),
                                     reinterpret_cast<const std::uint8_t*>(text.data()),
                                     text.size());
    start = end + 1;
  }
  relume::fuzz::expect_only_relume_errors([&] { relume::load_field(field_folder()); });
  return 0;
}
