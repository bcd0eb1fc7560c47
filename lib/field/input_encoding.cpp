// The input-encoding rule for fields.
#include "field/input_encoding.hpp"

#include <relume/error.hpp>

#include "image/image_encoding.hpp"

namespace relume {

InputEncodingDecision decide_input_encoding(const FieldSource& source, EightBitEncoding requested) {
  if (requested == EightBitEncoding::linear) return {requested, "linear, as asked"};
  if (requested == EightBitEncoding::srgb) return {requested, "sRGB-decoded, as asked"};
  const StoredEncoding stored = read_stored_encoding(source.images.front());
  const std::string kind = std::to_string(stored.bits) + "-bit " + stored.format;
  if (stored.floating) return {EightBitEncoding::linear, kind + " (floating point): linear"};
  if (stored.bits > 8) return {EightBitEncoding::linear, kind + ": linear"};
  if (source.intensities.rows() > 0)
    return {EightBitEncoding::linear,
            kind + " in a DiLiGenT folder (light_intensities.txt): linear sensor values"};
  if (is_linear_color_space(stored.color_space))
    return {EightBitEncoding::linear, kind + ", declared " + stored.color_space + ": linear"};
  return {EightBitEncoding::srgb,
          kind +
              (stored.color_space.empty() ? ", no colour space declared"
                                          : ", declared " + stored.color_space) +
              ": decoded as sRGB"};
}

InputEncodingDecision decide_input_encoding(const std::filesystem::path& path,
                                            EightBitEncoding requested) {
  return decide_input_encoding(describe_field(path), requested);
}

EightBitEncoding parse_input_encoding(const std::string& text) {
  if (text == "auto") return EightBitEncoding::automatic;
  if (text == "linear") return EightBitEncoding::linear;
  if (text == "srgb") return EightBitEncoding::srgb;
  throw Error("input encoding '" + text + "' is invalid: expected auto, linear or srgb");
}

}  // namespace relume
