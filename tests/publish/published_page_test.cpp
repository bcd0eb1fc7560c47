// The published page in a real browser: `relume publish` writes the site of a small synthetic
// container in 16-pixel tiles (three pyramid levels), a static server (cpp-httplib, in this
// process) serves it, and headless Chromium (WebGL2 on SwiftShader) opens it with a light or a
// turned map, a residual cap and an exposure in the URL; the full-resolution image it reads back
// (readback=1, through --dump-dom; workers=0, since --dump-dom's virtual time does not wait for
// the tile decoding workers that the benchmark's real-time runs use) must equal `relume
// relight`'s PNG of the same settings within one 8-bit code on at least 99.9% of the pixels. Two
// containers: a masked one with quantized values, and an unmasked one in the Haar basis with
// dark pixels and float values; two caps each, lights inside the captured cover and outside it
// (lit from the rim), a lat-long map at two rotations. A one-basis container (a rate target's)
// is published with its JPEG 2000 codestream as it is, which the page decodes (OpenJPEG built
// for WebAssembly): the same image, data files near the container's bytes, and a truncated
// codestream named on the status line. Without WebGL2 the page says so. The browser tests skip,
// saying why, when Chromium is not installed.
#include <array>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <thread>

#include "support/test_support.hpp"
// After Eigen: httplib.h brings in <resolv.h>, whose _res macro breaks Eigen's headers.
#include <httplib.h>

namespace relume::testing {
namespace {

namespace fs = std::filesystem;

// The Chromium binary, or empty when none is installed.
std::string chromium_binary() {
  for (const char* name : {"chromium", "chromium-browser"}) {
    const CommandResult found = run_command(std::string("command -v ") + name);
    if (found.exit_code == 0 && !found.output.empty())
      return found.output.substr(0, found.output.find('\n'));
  }
  return "";
}

#define REQUIRE_CHROMIUM(var)                                                               \
  const std::string var = chromium_binary();                                                \
  if (var.empty())                                                                          \
  GTEST_SKIP() << "Chromium is not installed (neither chromium nor chromium-browser is on " \
                  "PATH; Debian: apt-get install chromium): the published page is not tested"

// A static file server on a free port of 127.0.0.1 for the lifetime of the object.
class StaticServer {
 public:
  explicit StaticServer(const fs::path& folder) {
    server_.set_file_extension_and_mimetype_mapping("js", "text/javascript");
    server_.set_file_extension_and_mimetype_mapping("bin", "application/octet-stream");
    EXPECT_TRUE(server_.set_mount_point("/", folder.string()));
    port_ = server_.bind_to_any_port("127.0.0.1");
    thread_ = std::thread([this] { server_.listen_after_bind(); });
    while (!server_.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ~StaticServer() {
    server_.stop();
    thread_.join();
  }
  std::string url(const std::string& path) const {
    return "http://127.0.0.1:" + std::to_string(port_) + "/" + path;
  }

 private:
  httplib::Server server_;
  std::thread thread_;
  int port_ = 0;
};

// The DOM of `url` after its scripts ran (up to 60 s of virtual time), in headless Chromium.
std::string page_dom(const std::string& chromium, const std::string& url,
                     const std::string& extra_flags = "") {
  TempDir profile;
  const CommandResult result =
      run_command("'" + chromium + "' --headless --no-sandbox --enable-unsafe-swiftshader " +
                  "--user-data-dir='" + profile.path().string() + "' --virtual-time-budget=60000 " +
                  extra_flags + " --dump-dom '" + url + "' 2>/dev/null");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  return result.output;
}

std::vector<std::uint8_t> decode_base64(const std::string& text) {
  std::array<int, 256> value;
  value.fill(-1);
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  for (std::size_t i = 0; i < alphabet.size(); ++i) value[std::uint8_t(alphabet[i])] = int(i);
  std::vector<std::uint8_t> bytes;
  std::uint32_t bits = 0;
  int count = 0;
  for (char ch : text) {
    if (value[std::uint8_t(ch)] < 0) continue;  // padding, whitespace
    bits = (bits << 6) | std::uint32_t(value[std::uint8_t(ch)]);
    if ((count += 6) >= 8) bytes.push_back(std::uint8_t(bits >> (count -= 8)));
  }
  return bytes;
}

struct PageImage {
  std::string state;               // <body data-state>
  std::string status;              // the status line
  std::vector<std::uint8_t> rgba;  // canvas bytes, rows from the top
};

PageImage open_page(const std::string& chromium, const std::string& url,
                    const std::string& extra_flags = "") {
  const std::string dom = page_dom(chromium, url, extra_flags);
  PageImage page;
  std::smatch match;
  if (std::regex_search(dom, match, std::regex(R"re(<body data-state="([a-z0-9-]+)")re")))
    page.state = match[1];
  if (std::regex_search(dom, match, std::regex(R"re(<span id="status" role="status">([^<]*)<)re")))
    page.status = match[1];
  if (std::regex_search(dom, match,
                        std::regex(R"re(<pre id="readback" hidden="">([^<]*)</pre>)re")))
    page.rgba = decode_base64(match[1]);
  return page;
}

class PublishedPage : public CommandSuite {
 protected:
  static void SetUpTestSuite() {
    CommandSuite::SetUpTestSuite();
    // Masked: the synthetic scene's object mask, quantized values. Unmasked, in the Haar basis,
    // its background stored as dark pixels (a noise floor above the scene's dark ground), float
    // values (the page's other shader).
    run_or_fail("synth -o '" + path("scene") + "' --size 48x40 --lights 40 --samples 1");
    run_or_fail("compress '" + path("scene") + "' -o '" + path("masked.relume") +
                "' --clusters 4 --terms 2 --residual 6");
    run_or_fail("compress '" + path("scene") + "' -o '" + path("haar.relume") +
                "' --no-mask --transform haar --noise-floor 0.02 --clusters 4 --terms 3 "
                "--residual 5 --weights-precision float32 --residual-precision float32");
    // One basis (a rate target's model): weights stored as JPEG 2000 planes, decoded by the page.
    run_or_fail("compress '" + path("scene") + "' -o '" + path("one_basis.relume") +
                "' --target-models one-basis --target-bytes 5000");
    run_or_fail("sky -o '" + path("sky.exr") + "' --width 64 --sun-radiance 200");
    run_or_fail("publish '" + path("masked.relume") + "' --env '" + path("sky.exr") + "' -o '" +
                path("masked_site") + "' --title 'Masked scene' --tile-size 16");
    run_or_fail("publish '" + path("haar.relume") + "' -o '" + path("haar_site") +
                "' --tile-size 16");
  }

  // Opens the site with the settings in the URL and compares the canvas with `relume relight`.
  // The light: a direction "x,y,z", or "sky@DEGREES" for the published map turned.
  static void expect_page_equals_relight(const std::string& chromium, const std::string& name,
                                         const std::string& light, int cap, double exposure) {
    SCOPED_TRACE(name + ", light " + light + ", cap " + std::to_string(cap));
    const std::string reference = path(name + "_" + std::to_string(cap) + "_" + light + ".png");
    const bool map = light.starts_with("sky@");
    const std::string degrees = map ? light.substr(4) : "";
    run_or_fail(
        "relight '" + path(name + ".relume") + "' " +
        (map ? "--env '" + path("sky.exr") + "' --rotate " + degrees : "--light-dir " + light) +
        " --residual " + std::to_string(cap) + " --exposure " + std::to_string(exposure) + " -o '" +
        reference + "'");
    const Image expected = read_image(reference);
    StaticServer server(path(name + "_site"));
    const PageImage page = open_page(
        chromium, server.url("index.html?readback=1&workers=0&" +
                             (map ? "env=0&rotate=" + degrees : "light=" + light) + "&residual=" +
                             std::to_string(cap) + "&exposure=" + std::to_string(exposure)));
    ASSERT_EQ(page.state, "ready") << page.status;
    const std::size_t pixels = std::size_t(expected.width) * expected.height;
    ASSERT_EQ(page.rgba.size(), pixels * 4);
    std::size_t within = 0, lit = 0, largest = 0;
    for (std::size_t p = 0; p < pixels; ++p) {
      int difference = 0;
      for (int c = 0; c < 3; ++c) {
        const int code = int(std::lround(
            expected.pixels[p * expected.channels + std::min(c, expected.channels - 1)] * 255.0f));
        difference = std::max(difference, std::abs(code - int(page.rgba[p * 4 + c])));
        lit += c == 0 && code > 8;
      }
      within += difference <= 1;
      largest = std::max<std::size_t>(largest, difference);
    }
    EXPECT_GE(double(within), 0.999 * double(pixels))
        << within << " of " << pixels << " pixels within one code, largest difference " << largest;
    // A real image, not a black frame that would match a black reference.
    EXPECT_GT(lit, pixels / 10) << "only " << lit << " pixels above code 8";
  }
};

TEST_F(PublishedPage, MaskedFieldEqualsRelightAtTwoCapsInsideAndOutsideTheCover) {
  REQUIRE_CHROMIUM(chromium);
  for (int cap : {0, 3}) {
    expect_page_equals_relight(chromium, "masked", "0.3,0.5,0.8", cap, 1.0);
    expect_page_equals_relight(chromium, "masked", "-0.9,0.1,-0.4", cap, 1.0);
  }
}

TEST_F(PublishedPage, MaskedFieldUnderATurnedMapEqualsRelight) {
  REQUIRE_CHROMIUM(chromium);
  for (const char* turned : {"sky@0", "sky@130"})
    expect_page_equals_relight(chromium, "masked", turned, 3, -2.0);
}

TEST_F(PublishedPage, HaarFieldWithDarkPixelsEqualsRelightAtTwoCaps) {
  REQUIRE_CHROMIUM(chromium);
  for (int cap : {1, 5}) expect_page_equals_relight(chromium, "haar", "-0.4,0.2,0.9", cap, 0.5);
}

// The bytes of the files under `folder`.
std::uint64_t folder_bytes(const fs::path& folder) {
  std::uint64_t bytes = 0;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.is_regular_file()) bytes += entry.file_size();
  return bytes;
}

// The one-basis model's site holds the container's codestream as it is (data/weights.j2k) with
// its terms' colour transforms in the manifest, tiles without weights and the page's decoder; a
// full view's data files weigh about what the container does, and the page relights as the
// container does. Clustered sites go without the decoder.
TEST_F(PublishedPage, OneBasisFieldShipsItsCodestreamAndEqualsRelight) {
  const CommandResult published = run_relume("publish '" + path("one_basis.relume") + "' -o '" +
                                             path("one_basis_site") + "' --tile-size 16");
  ASSERT_EQ(published.exit_code, 0) << published.output;
  EXPECT_THAT(published.output, ::testing::HasSubstr("the container's JPEG 2000 codestream"));
  const fs::path site = path("one_basis_site");
  const auto manifest = nlohmann::json::parse(std::ifstream(site / "manifest.json"));
  EXPECT_EQ(manifest["weight_planes"]["file"], "data/weights.j2k");
  EXPECT_EQ(manifest["weight_planes"]["planes"], 3 * manifest["field"]["terms"].get<int>());
  // Each term's colour transform (three angles), which the page undoes as relume's reader does.
  EXPECT_EQ(manifest["weight_planes"]["colour_angles"].size(),
            3 * manifest["field"]["terms"].get<std::size_t>());
  for (const auto& array : manifest["tiles"]["arrays"]) EXPECT_NE(array["name"], "weights");
  EXPECT_TRUE(fs::exists(site / "openjpeg" / "j2k_decode.wasm.gz"));
  EXPECT_FALSE(fs::exists(fs::path(path("masked_site")) / "openjpeg"));
  const std::uint64_t container = fs::file_size(path("one_basis.relume"));
  const std::uint64_t data = fs::file_size(site / "data" / "field.bin") +
                             fs::file_size(site / "data" / "weights.j2k") +
                             folder_bytes(site / "data" / "tiles" / "0");
  EXPECT_LE(double(data), 1.1 * double(container))
      << "a full view's data files weigh " << data << " bytes, the container " << container;
  REQUIRE_CHROMIUM(chromium);
  expect_page_equals_relight(chromium, "one_basis", "0.3,0.5,0.8", 0, 1.0);
}

TEST_F(PublishedPage, NamesATruncatedWeightCodestream) {
  run_or_fail("publish '" + path("one_basis.relume") + "' -o '" + path("truncated_site") + "'");
  const fs::path weights = fs::path(path("truncated_site")) / "data" / "weights.j2k";
  fs::resize_file(weights, fs::file_size(weights) / 2);
  REQUIRE_CHROMIUM(chromium);
  StaticServer server(path("truncated_site"));
  const PageImage page = open_page(chromium, server.url("index.html?workers=0"));
  EXPECT_EQ(page.state, "error");
  EXPECT_THAT(page.status,
              ::testing::HasSubstr("data/weights.j2k: the JPEG 2000 codestream does not decode"));
}

TEST_F(PublishedPage, SaysSoWithoutWebGl2) {
  REQUIRE_CHROMIUM(chromium);
  StaticServer server(path("masked_site"));
  const PageImage page = open_page(chromium, server.url("index.html"), "--disable-3d-apis");
  EXPECT_EQ(page.state, "no-webgl2");
  EXPECT_THAT(page.status, ::testing::HasSubstr("This page needs WebGL2"));
}

TEST_F(PublishedPage, ManifestDescribesThePyramidAndItsTiles) {
  const auto manifest =
      nlohmann::json::parse(std::ifstream(fs::path(path("haar_site")) / "manifest.json"));
  EXPECT_EQ(manifest["title"], "haar.relume");
  EXPECT_EQ(manifest["field"]["transform"], "haar");
  EXPECT_GT(manifest["field"]["dark_pixels"].get<int>(), 0);
  // 48 x 40 in 16-pixel tiles: 3 x 3, then 24 x 20 (2 x 2), then 12 x 10 (one tile).
  const auto& levels = manifest["tiles"]["levels"];
  ASSERT_EQ(levels.size(), 3u);
  for (std::size_t level = 0; level < levels.size(); ++level)
    for (int column = 0; column < levels[level]["columns"].get<int>(); ++column)
      for (int row = 0; row < levels[level]["rows"].get<int>(); ++row)
        EXPECT_TRUE(
            fs::exists(fs::path(path("haar_site")) / "data" / "tiles" / std::to_string(level) /
                       (std::to_string(column) + "_" + std::to_string(row) + ".bin")))
            << "level " << level << " tile " << column << ", " << row;
  std::vector<std::string> arrays;
  for (const auto& array : manifest["tiles"]["arrays"]) arrays.push_back(array["name"]);
  EXPECT_THAT(arrays, ::testing::Contains("dark_pixels"));
  EXPECT_THAT(arrays, ::testing::Contains("dark_gains"));
  EXPECT_EQ(nlohmann::json::parse(
                std::ifstream(fs::path(path("masked_site")) / "manifest.json"))["title"],
            "Masked scene");
  const CommandResult bad_map =
      run_relume("publish '" + path("masked.relume") + "' --env '" + path("masked.relume") +
                 "' -o '" + path("bad_site") + "'");
  EXPECT_NE(bad_map.exit_code, 0);
  EXPECT_FALSE(fs::exists(path("bad_site"))) << "a failed publish left a folder behind";
}

TEST_F(PublishedPage, ResidualOptionCutsTheRowsItPublishes) {
  run_or_fail("publish '" + path("masked.relume") + "' -o '" + path("cut_site") + "' --residual 2");
  const auto manifest =
      nlohmann::json::parse(std::ifstream(fs::path(path("cut_site")) / "manifest.json"));
  EXPECT_EQ(manifest["field"]["residual_longest_row"], 2);
  const CommandResult refused =
      run_relume("publish '" + path("masked.relume") + "' -o '" + path("cut_site") + "'");
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_THAT(refused.output, ::testing::HasSubstr("cut_site"));
  // -y replaces the site, its data folder whole.
  run_or_fail("publish '" + path("masked.relume") + "' -o '" + path("cut_site") + "' -y");
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(fs::path(path("cut_site")) /
                                                "manifest.json"))["field"]["residual_longest_row"],
            6);
}

}  // namespace
}  // namespace relume::testing
