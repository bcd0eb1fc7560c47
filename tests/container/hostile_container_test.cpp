// Tests of the container reader on crafted files whose sizes lie: a few hundred bytes that claim
// 65536 x 65535 pixels (the mask's runs are valid, its size is not), a field at the pixel limit
// under a small memory budget, a zero-length light direction, and a zstd section whose table
// claims more than any frame of its size can decode to. Each is refused by name before anything
// of the claimed size is allocated. A stored size of 2^49 is named as running past the file's end
// (not as a wrapped ratio), and a NaN dark value is named in section 'dark'.
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <relume/error.hpp>

#include "container/container.hpp"
#include "container/container_bytes.hpp"
#include "container/container_format.hpp"
#include "container/section_coding.hpp"
#include "core/memory_budget.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using testing::error_message;
using ::testing::HasSubstr;

// A container of `width` x `height` one-channel pixels, one light, nothing stored (an all-outside
// mask): every section valid, written with the real frame code. `header_keys` are added to (or
// replace keys of) its header. With a `dark` value, every pixel is inside the mask and dark, and
// the dark model of the one light and channel is that value.
std::string crafted_container(std::int64_t width, std::int64_t height, const float direction[3],
                              const nlohmann::json& header_keys = nlohmann::json::object(),
                              std::optional<float> dark = std::nullopt) {
  nlohmann::json header = {{"width", width},
                           {"height", height},
                           {"channels", 1},
                           {"lights", 1},
                           {"terms", 0},
                           {"clusters", 0},
                           {"transform", "identity"},
                           {"stored_rows", 0},
                           {"residual_nonzeros", 0},
                           {"weights_precision", "float32"},
                           {"residual_precision", "float32"},
                           {"weight_step", 0},
                           {"weight_coding", "values"},
                           {"weight_planes_step", 0},
                           {"residual_step", 0},
                           {"basis_bits", 0},
                           {"cluster_id_bits", 8},
                           {"residual_length_bits", 8},
                           {"light_index_bits", 8},
                           {"dark_gain_step", 0},
                           {"dark_gain_block", 8},
                           {"parameters", nlohmann::json::object()}};
  header.update(header_keys);
  ByteWriter lights;
  for (int c = 0; c < 3; ++c) lights.f32(direction[c]);
  for (int c = 0; c < 3; ++c) lights.f32(1.0f);
  const std::uint64_t pixels = std::uint64_t(width * height);
  // Run-length sets: one absent run over everything (no pixel inside, none dark).
  ByteWriter mask, functions, dark_pixels, dark_values;
  for (ByteWriter* set : {&mask, &functions, &dark_pixels}) {
    set->u8(1);
    set->varint(pixels);
  }
  if (dark) {  // one absent run of 0, then every pixel present
    mask = ByteWriter(), dark_pixels = ByteWriter();
    for (ByteWriter* set : {&mask, &dark_pixels}) {
      set->u8(1);
      set->varint(0);
      set->varint(pixels);
    }
    dark_values.f32(*dark);
  }
  std::vector<StoredSection> sections;
  for (std::string_view name : container_section_names(container_format_version)) {
    StoredSection section{name, "", 1};
    if (name == "header") section.raw = header.dump();
    if (name == "lights") section.raw = lights.data();
    if (name == "mask") section.raw = mask.data();
    if (name == "functions") section.raw = functions.data();
    if (name == "dark_pixels") section.raw = dark_pixels.data();
    if (name == "dark") section.raw = dark_values.data();
    sections.push_back(section);
  }
  return assemble_container(sections, /*entropy_coding=*/false, /*threads=*/1, nullptr);
}

const float up[3] = {0, 1, 0};

TEST(HostileContainer, TheCraftedFileIsValidAtASaneSize) {
  const CompressedField field = decode_container(crafted_container(7, 5, up), "small.relume");
  EXPECT_EQ(field.mask.size(), 35u);
  EXPECT_EQ(field.stored_rows(), 0u);
}

TEST(HostileContainer, TheNonNegativeMarkIsABooleanOrAbsent) {
  EXPECT_FALSE(decode_container(crafted_container(7, 5, up), "unmarked.relume").non_negative);
  EXPECT_TRUE(decode_container(crafted_container(7, 5, up, {{"non_negative", true}}), "m.relume")
                  .non_negative);
  EXPECT_THAT(
      error_message([&] {
        decode_container(crafted_container(7, 5, up, {{"non_negative", "yes"}}), "bad.relume");
      }),
      HasSubstr("bad.relume: section 'header': 'non_negative' is not true or false"));
}

TEST(HostileContainer, WeightCodingsAndPlaneStepsOutsideTheFormatAreRefused) {
  const auto message = [](const nlohmann::json& keys) {
    return error_message([&] { decode_container(crafted_container(7, 5, up, keys), "w.relume"); });
  };
  EXPECT_THAT(message({{"weight_coding", "wavelet"}}),
              HasSubstr("w.relume: section 'header': 'weight_coding' is \"wavelet\", expected "
                        "\"values\" or \"jpeg2000_planes\""));
  EXPECT_THAT(message({{"weight_planes_step", 0.5}}),
              HasSubstr("'weight_planes_step' is 0.5, expected 0 for values that are not "
                        "quantized"));
  EXPECT_THAT(message({{"weight_coding", "jpeg2000_planes"}, {"weight_planes_step", -1}}),
              HasSubstr("'weight_planes_step' is -1, expected a positive step"));
  // Planes for a field without terms: nothing to decode them into, refused by the section.
  EXPECT_THAT(message({{"weight_coding", "jpeg2000_planes"}, {"weight_planes_step", 1}}),
              HasSubstr("section 'weight_planes': a field without terms has no weight planes"));
}

TEST(HostileContainer, PixelCountsBeyondTheLimitAreRefusedBeforeAllocating) {
  const std::string bytes = crafted_container(65536, 65535, up);
  EXPECT_LT(bytes.size(), 2048u);
  EXPECT_THAT(error_message([&] { decode_container(bytes, "huge.relume"); }),
              HasSubstr("huge.relume: section 'header': 65536x65535 pixels is more than the "
                        "1073741824 a container may hold"));
}

TEST(HostileContainer, DecodingBeyondTheMemoryBudgetIsRefusedWithTheNumbers) {
  const std::string bytes = crafted_container(32768, 32768, up);
  set_memory_limit(64 << 20);
  const std::string message = error_message([&] { decode_container(bytes, "big.relume"); });
  set_memory_limit(0);
  EXPECT_THAT(message, HasSubstr("reading big.relume (32768x32768 pixels) needs about"));
  EXPECT_THAT(message, HasSubstr("more than the 64.0 MB available (--memory-limit)"));
}

TEST(HostileContainer, ZeroLengthLightDirectionsAreRefused) {
  const float zero[3] = {0, 0, 0};
  EXPECT_THAT(error_message([&] { decode_container(crafted_container(3, 2, zero), "z.relume"); }),
              HasSubstr("z.relume: section 'lights': the direction of light 0 has zero length"));
}

TEST(HostileContainer, ZstdSectionsCannotClaimMoreThanAFrameDecodesTo) {
  const SectionCoding zstd{true, SectionFilter::none, 1};
  EXPECT_THAT(error_message([&] {
                decode_section(std::string(100, 'x'), zstd, 100ull * 32768 + 1, "f: section 'w'");
              }),
              HasSubstr("f: section 'w': 100 zstd-coded bytes cannot decode to 3276801 bytes"));
  // A real frame at a high ratio still decodes.
  const std::string zeros(1 << 20, '\0');
  const CodedSection coded = code_section(zeros, 1);
  ASSERT_TRUE(coded.coding.zstd);
  EXPECT_EQ(decode_section(coded.bytes, coded.coding, zeros.size(), "zeros"), zeros);
}

// The coded-size check multiplied the stored size by 32768: from 2^49 bytes the product wrapped,
// and the table was said to claim too much for its coded size. The truth is that the section runs
// past the end of the file.
TEST(HostileContainer, AStoredSizeOfTwoToTheFortyNineIsASectionPastTheEndOfTheFile) {
  const SectionCoding zstd{true, SectionFilter::none, 1};
  EXPECT_NO_THROW(check_coded_size(1ull << 49, 1ull << 62, zstd, "f: section 'w'"));
  EXPECT_NO_THROW(check_coded_size(~0ull, ~0ull, zstd, "f: section 'w'"));

  std::string bytes = crafted_container(7, 5, up);
  ParsedContainer parsed = parse_container(bytes, "huge.relume");
  std::size_t mask = 0;
  while (parsed.layout.sections[mask].name != "mask") ++mask;
  parsed.layout.sections[mask].bytes = 1ull << 49;
  parsed.codings[mask] = zstd;
  const std::string preamble = encode_preamble(parsed.layout, parsed.codings);
  bytes.replace(0, preamble.size(), preamble);
  const std::string message = error_message([&] { parse_container(bytes, "huge.relume"); });
  EXPECT_THAT(message, HasSubstr("huge.relume is truncated: section 'mask' needs bytes " +
                                 std::to_string(parsed.layout.sections[mask].offset) + " to "));
  EXPECT_THAT(message, HasSubstr("the file has " + std::to_string(bytes.size())));
  EXPECT_THAT(message, ::testing::Not(HasSubstr("cannot decode")));
}

// A NaN among the dark values was reported in section 'dark_pixels', which holds only positions.
TEST(HostileContainer, ANonFiniteDarkValueIsNamedInTheDarkSection) {
  const CompressedField field =
      decode_container(crafted_container(16, 8, up, nlohmann::json::object(), 0.25f), "d.relume");
  EXPECT_EQ(field.dark_pixels.size(), 128u);
  EXPECT_EQ(field.dark, std::vector<float>{0.25f});
  EXPECT_EQ(error_message([&] {
              decode_container(
                  crafted_container(16, 8, up, nlohmann::json::object(), std::nanf("")),
                  "d.relume");
            }),
            "d.relume: section 'dark': the dark value of channel 0 light 0 is nan, expected "
            "finite");
}

}  // namespace
}  // namespace relume
