// Tests of `relume view`'s HTTP API, run against the `relume` binary serving a small synthetic
// container on a free port (--port 0) and asked with cpp-httplib's client: /info describes the
// container; frames equal the Relighter's image of the same light and `relume relight`'s output
// with the same settings (directional light, maps, rotation, exposure, residual cap); the error
// and mask views hold what they say; bad parameters (random numbers in every numeric one among
// them) get 400 naming them, unknown paths 404, a
// request flood 429, and none of them stops the server; SIGINT and SIGTERM stop it with the
// command's exit status.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <relume/relight.hpp>
#include <thread>

#include "container/container.hpp"
#include "image/image_difference.hpp"
#include "lighting/light_interpolation.hpp"
#include "support/number_samples.hpp"
#include "support/test_support.hpp"
// After Eigen: httplib.h brings in <resolv.h>, whose _res macro breaks Eigen's headers.
#include <httplib.h>

extern char** environ;

namespace relume {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A `relume view` process, its output in a log file; stopped with SIGTERM if a test leaves it.
class ViewProcess {
 public:
  ViewProcess(const std::vector<std::string>& arguments, const fs::path& log) : log_(log) {
    std::vector<std::string> args = {RELUME_BINARY, "view"};
    args.insert(args.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    EXPECT_EQ(posix_spawn(&pid_, RELUME_BINARY, &actions, nullptr, argv.data(), environ), 0);
    posix_spawn_file_actions_destroy(&actions);
  }
  ~ViewProcess() {
    if (pid_ > 0) stop(SIGTERM);
  }

  // The port from the printed address, or 0 when the process ended (or took 60 s) before it.
  int wait_for_port() {
    const std::regex address("relume view: http://[^ ]*:([0-9]+)/");
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
      std::smatch match;
      const std::string log = read_text(log_);
      if (std::regex_search(log, match, address)) return std::stoi(match[1]);
      if (exited()) return 0;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return 0;
  }

  // Sends `signal_number` and returns the exit status (1000 + signal when killed by one).
  int stop(int signal_number) {
    if (!exited()) kill(pid_, signal_number);
    return wait_exit();
  }

  // The exit status; a process still running after 60 s is killed (status 1009).
  int wait_exit() {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!exited() && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (!exited()) {
      kill(pid_, SIGKILL);
      int status = 0;
      waitpid(pid_, &status, 0);
      status_ = 1000 + SIGKILL;
    }
    pid_ = -1;
    return status_;
  }

  std::string log() const { return read_text(log_); }

 private:
  bool exited() {
    if (status_ >= 0) return true;
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) != pid_) return false;
    status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
    return true;
  }

  fs::path log_;
  pid_t pid_ = -1;
  int status_ = -1;
};

class ViewServer : public testing::CommandSuite {
 protected:
  static void SetUpTestSuite() {
    CommandSuite::SetUpTestSuite();
    make_small_scene();
    run_or_fail("sky -o '" + path("sky.exr") + "' --width 128");
    run_or_fail("sky -o '" + path("dusk.exr") +
                "' --width 128 --sun-elevation 8 --sun-azimuth 120");
  }

  // Starts `relume view scene.relume --port 0 ARGS` and connects a client to it.
  void start(const std::vector<std::string>& arguments = {"--env", path("sky.exr"), "--env",
                                                          path("dusk.exr")}) {
    std::vector<std::string> all = {"-q", path("scene.relume"), "--port", "0"};
    all.insert(all.end(), arguments.begin(), arguments.end());
    server_ = std::make_unique<ViewProcess>(all, path("server.log"));
    port_ = server_->wait_for_port();
    ASSERT_GT(port_, 0) << server_->log();
    client_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
    client_->set_read_timeout(60, 0);
  }

  httplib::Result get(const std::string& target) {
    httplib::Result result = client_->Get(target.c_str());
    EXPECT_TRUE(result) << target << ": no answer; server log:\n" << server_->log();
    return result;
  }

  // The frame `target` answers, decoded (status 200 expected).
  Image frame(const std::string& target, const std::string& extension) {
    const httplib::Result result = get(target);
    if (!result) return {};
    EXPECT_EQ(result->status, 200) << target << ": " << result->body;
    const fs::path file = path("frame" + extension);
    std::ofstream(file, std::ios::binary) << result->body;
    return read_image(file);
  }

  // `relume relight scene.relume ARGS -o relit.png`, decoded.
  Image relight(const std::string& arguments) {
    run_or_fail("-q -y relight '" + path("scene.relume") + "' " + arguments + " -o '" +
                path("relit.png") + "'");
    return read_image(path("relit.png"));
  }

  std::unique_ptr<ViewProcess> server_;
  std::unique_ptr<httplib::Client> client_;
  int port_ = 0;
};

void expect_same_pixels(const Image& a, const Image& b, const std::string& what) {
  ASSERT_EQ(a.width, b.width) << what;
  ASSERT_EQ(a.height, b.height) << what;
  ASSERT_EQ(a.channels, b.channels) << what;
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) differing += a.pixels[i] != b.pixels[i];
  EXPECT_EQ(differing, 0u) << what << ": values that differ";
}

TEST_F(ViewServer, InfoDescribesTheContainer) {
  start();
  const httplib::Result result = get("/info");
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200);
  const auto info = nlohmann::json::parse(result->body);
  const CompressedField field = read_container(path("scene.relume"));
  EXPECT_EQ(info["width"], 24);
  EXPECT_EQ(info["height"], 20);
  EXPECT_EQ(info["channels"], 3);
  EXPECT_EQ(info["lights"], 40);
  EXPECT_EQ(info["clusters"], 4);
  EXPECT_EQ(info["terms"], 2);
  EXPECT_EQ(info["residual_entries_max"], int(field.residual.longest_row()));
  EXPECT_GT(info["residual_entries_max"].get<int>(), 0);
  EXPECT_EQ(info["stored_functions"], field.stored_rows());
  ASSERT_EQ(info["light_directions"].size(), 40u);
  for (int i = 0; i < 40; ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(info["light_directions"][i][k].get<float>(), field.directions(i, k));
  EXPECT_EQ(info["maps"], nlohmann::json({"sky.exr", "dusk.exr"}));
  EXPECT_FALSE(info["device"].get<std::string>().empty());
  const auto& defaults = info["defaults"];
  EXPECT_TRUE(defaults["light"].is_null());
  EXPECT_EQ(defaults["map"], 0);
  EXPECT_EQ(defaults["rotate"], 0);
  EXPECT_EQ(defaults["exposure"], 0);
  EXPECT_EQ(defaults["residual"], "all");
  EXPECT_EQ(defaults["color"], nlohmann::json({1, 1, 1}));
  EXPECT_EQ(info["requests_per_second"], 120);
}

TEST_F(ViewServer, ExrFrameEqualsTheRelightersImage) {
  start();
  const CompressedField field = read_container(path("scene.relume"));
  const Eigen::Vector3d direction(0.3, 0.5, 0.8), color(1.0, 0.5, 0.25);
  const LightRgb light = LightInterpolation(field.directions).light_vector({direction, color, 0});
  Relighter relighter(field);
  for (const int cap : {all_residual_entries, 2}) {
    const Image expected = relighter.relight(light, cap);
    const std::string residual = cap == all_residual_entries ? "all" : std::to_string(cap);
    const Image served = frame(
        "/frame?light=0.3,0.5,0.8&color=1,0.5,0.25&residual=" + residual + "&format=exr", ".exr");
    ASSERT_EQ(served.pixels.size(), expected.pixels.size());
    double largest = 0, worst = 0;
    for (std::size_t i = 0; i < served.pixels.size(); ++i) {
      largest = std::max(largest, double(std::abs(expected.pixels[i])));
      worst = std::max(worst, double(std::abs(served.pixels[i] - expected.pixels[i])));
    }
    EXPECT_GT(largest, 0.01) << "the frame is lit";
    EXPECT_LE(worst, 1e-6 * largest) << "residual " << residual;
  }
}

TEST_F(ViewServer, FramesEqualRelightWithTheSameSettings) {
  start();
  expect_same_pixels(frame("/frame", ".png"), relight("--env '" + path("sky.exr") + "'"),
                     "the defaults: the first map, unturned");
  expect_same_pixels(frame("/frame?rotate=75&exposure=1.5&residual=2", ".png"),
                     relight("--env '" + path("sky.exr") +
                             "' --rotate 75 --exposure 1.5 "
                             "--residual 2"),
                     "map 0 turned 75 degrees");
  expect_same_pixels(frame("/frame?map=1&rotate=200", ".png"),
                     relight("--env '" + path("dusk.exr") + "' --rotate 200"),
                     "map 1 turned 200 degrees");
  expect_same_pixels(frame("/frame?light=-0.4,0.2,0.9&spread=5&exposure=-0.5&color=2,1,1", ".png"),
                     relight("--light-dir -0.4,0.2,0.9 --spread 5 --exposure -0.5 "
                             "--light-color 2,1,1"),
                     "a moved disc light");
  const Image changed = frame("/frame?rotate=150", ".png");
  EXPECT_GT(testing::relative_squared_difference(changed, frame("/frame", ".png")), 1e-4)
      << "turning the map changes the frame";
}

TEST_F(ViewServer, WithoutMapsTheDefaultLightComesFromTheCamera) {
  start({});
  expect_same_pixels(frame("/frame", ".png"), relight("--light-dir 0,0,1"),
                     "the default directional light");
  const httplib::Result rotated = get("/frame?rotate=10");
  ASSERT_TRUE(rotated);
  EXPECT_EQ(rotated->status, 400);
  EXPECT_THAT(rotated->body, ::testing::HasSubstr("rotate=10"));
  EXPECT_THAT(rotated->body, ::testing::HasSubstr("without --env"));
}

TEST_F(ViewServer, ResidualCapErrorIsMeasuredAndShown) {
  start();
  const CompressedField field = read_container(path("scene.relume"));
  const LightRgb light = LightInterpolation(field.directions).light_vector({{0.2, 0.3, 0.9}});
  Relighter relighter(field);
  const Image capped = relighter.relight(light, 0), full = relighter.relight(light);
  const double expected_error = image_difference(capped, full).relative_squared_error;
  ASSERT_GT(expected_error, 0) << "the residual matters in this field";

  const httplib::Result result = get("/frame?light=0.2,0.3,0.9&residual=0");
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << result->body;
  EXPECT_NEAR(std::stod(result->get_header_value("X-Relume-Residual-Error")), expected_error,
              1e-4 * expected_error);
  EXPECT_EQ(result->get_header_value("X-Relume-Residual-Cap"), "0");
  EXPECT_GE(std::stod(result->get_header_value("X-Relume-Render-Ms")), 0);
  const httplib::Result exact = get("/frame?light=0.2,0.3,0.9");
  ASSERT_TRUE(exact);
  EXPECT_EQ(std::stod(exact->get_header_value("X-Relume-Residual-Error")), 0);
  EXPECT_EQ(exact->get_header_value("X-Relume-Residual-Cap"), "all");

  const Image difference =
      frame("/frame?light=0.2,0.3,0.9&residual=0&view=error&format=exr", ".exr");
  ASSERT_EQ(difference.pixels.size(), full.pixels.size());
  double worst = 0;
  for (std::size_t i = 0; i < full.pixels.size(); ++i)
    worst = std::max(worst, std::abs(double(difference.pixels[i]) -
                                     std::abs(double(capped.pixels[i]) - full.pixels[i])));
  EXPECT_LE(worst, 1e-6);

  // The false colour is black exactly where the cap changes nothing.
  const Image colours = frame("/frame?light=0.2,0.3,0.9&residual=0&view=error", ".png");
  ASSERT_EQ(colours.channels, 3);
  std::size_t mismatched = 0, coloured = 0;
  for (std::size_t p = 0; p < std::size_t(colours.width) * colours.height; ++p) {
    const bool differs = difference.pixels[p * 3] > 0 || difference.pixels[p * 3 + 1] > 0 ||
                         difference.pixels[p * 3 + 2] > 0;
    const bool black = colours.pixels[p * 3] == 0 && colours.pixels[p * 3 + 1] == 0 &&
                       colours.pixels[p * 3 + 2] == 0;
    mismatched += differs == black;
    coloured += !black;
  }
  EXPECT_GT(coloured, 0u);
  EXPECT_EQ(mismatched, 0u);
}

TEST_F(ViewServer, MaskViewShowsTheStoredPixels) {
  start();
  const CompressedField field = read_container(path("scene.relume"));
  const Image mask = frame("/frame?view=mask&format=exr", ".exr");
  ASSERT_EQ(mask.width, field.width);
  ASSERT_EQ(mask.channels, 3);
  std::vector<std::uint8_t> stored(field.mask.size(), 0);
  for (const std::uint32_t function : field.stored_function) stored[function / field.channels] = 1;
  std::size_t white = 0, black = 0;
  for (std::size_t p = 0; p < stored.size(); ++p) {
    const bool is_white = mask.pixels[p * 3] == 1 && mask.pixels[p * 3 + 2] == 1;
    const bool is_black = mask.pixels[p * 3] == 0 && mask.pixels[p * 3 + 2] == 0;
    EXPECT_EQ(is_white, bool(stored[p])) << "pixel " << p;
    EXPECT_TRUE(field.mask[p] || is_black) << "pixel " << p << " is outside the mask";
    white += is_white;
    black += is_black;
  }
  EXPECT_GT(white, 0u);
  EXPECT_GT(black, 0u) << "the synthetic scene has a background outside its mask";
}

TEST_F(ViewServer, BadRequestsGet400NamingTheParameterAndTheServerStaysUp) {
  start();
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"exposure=nan", "exposure=nan"},
      {"exposure=inf", "exposure=inf"},
      {"exposure=1e9", "exposure=1e9"},
      {"exposure=bright", "exposure=bright"},
      {"light=1,2", "light=1,2"},
      {"light=0,0,0", "light=0,0,0"},
      {"light=a,b,c", "light=a,b,c"},
      {"light=nan,0,1", "light=nan,0,1"},
      {"rotate=inf", "rotate=inf"},
      {"map=2", "map=2"},
      {"map=-1", "map=-1"},
      {"residual=-1", "residual=-1"},
      {"residual=lots", "residual=lots"},
      {"format=gif", "format=gif"},
      {"view=normals", "view=normals"},
      {"color=-1,1,1", "color=-1,1,1"},
      {"spread=100&light=0,0,1", "spread=100"},
      {"light=0,0,1&rotate=3", "not both"},
      {"light=0,0,1&light=0,1,1", "'light'"},
      {"size=4096x4096", "unknown parameter 'size'"},
  };
  for (const auto& [query, named] : bad) {
    const httplib::Result result = get("/frame?" + query);
    ASSERT_TRUE(result) << query;
    EXPECT_EQ(result->status, 400) << query;
    EXPECT_THAT(result->body, ::testing::HasSubstr(named)) << query;
  }
  const httplib::Result missing = get("/nothing/here");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
  EXPECT_THAT(missing->body, ::testing::HasSubstr("/nothing/here"));
  const httplib::Result info = get("/info");
  ASSERT_TRUE(info);
  EXPECT_EQ(info->status, 200);
  EXPECT_EQ(frame("/frame", ".png").width, 24) << "the server still renders";
}

// Property: a random number (an edge such as 0, 1e400, inf or nan, or a random magnitude of
// either sign; fixed seed) in each numeric parameter gets a frame or a 400 naming the
// parameter, never a failure of the server, which still answers afterwards.
TEST_F(ViewServer, RandomNumbersInEveryNumericParameterGetAFrameOrA400) {
  start({"--env", path("sky.exr"), "--max-requests", "1000"});
  struct Parameter {
    std::string name;
    int numbers;
    std::string needs;
  };
  const std::vector<Parameter> parameters = {
      {"light", 3, ""},        {"color", 3, "light=0,0.3,1&"}, {"spread", 1, "light=0,0.3,1&"},
      {"rotate", 1, ""},       {"map", 1, ""},                 {"exposure", 1, ""},
      {"residual", 1, ""},
  };
  testing::NumberSamples samples(37);
  for (int request = 0; request < 56; ++request) {
    const Parameter& parameter = parameters[std::size_t(request) % parameters.size()];
    const std::string value = parameter.numbers == 3 ? samples.next_triple() : samples.next();
    const std::string target = "/frame?" + parameter.needs + parameter.name + "=" + value +
                               (request % 2 ? "&format=exr" : "");
    const httplib::Result result = get(target);
    ASSERT_TRUE(result) << target;
    EXPECT_TRUE(result->status == 200 || result->status == 400) << target << ": " << result->status;
    if (result->status == 400)
      EXPECT_THAT(result->body, ::testing::HasSubstr(parameter.name + "=")) << target;
  }
  EXPECT_EQ(get("/info")->status, 200) << server_->log();
}

TEST_F(ViewServer, ServesThePageAndItsFiles) {
  start();
  for (const char* target : {"/", "/viewer.js", "/viewer.css"}) {
    const httplib::Result result = get(target);
    ASSERT_TRUE(result) << target;
    EXPECT_EQ(result->status, 200) << target;
    EXPECT_GT(result->body.size(), 500u) << target;
  }
  EXPECT_THAT(get("/")->body, ::testing::HasSubstr("<script src=\"/viewer.js\">"));
}

TEST_F(ViewServer, RequestFloodsGet429) {
  start({"--max-requests", "5"});
  int refused = 0;
  for (int i = 0; i < 20; ++i) {
    const httplib::Result result = get("/info");
    ASSERT_TRUE(result);
    if (result->status == 429) {
      ++refused;
      EXPECT_THAT(result->body, ::testing::HasSubstr("too many requests"));
    }
  }
  EXPECT_GE(refused, 10);
  std::this_thread::sleep_for(std::chrono::milliseconds(1200));
  EXPECT_EQ(get("/info")->status, 200) << "the bucket refills";
}

TEST_F(ViewServer, SigintAndSigtermStopItWithTheCommandsExitStatus) {
  for (const int signal_number : {SIGINT, SIGTERM}) {
    start();
    ASSERT_EQ(get("/frame?format=jpeg")->status, 200);
    const auto sent = std::chrono::steady_clock::now();
    EXPECT_EQ(server_->stop(signal_number), 128 + signal_number) << server_->log();
    EXPECT_LT(std::chrono::steady_clock::now() - sent, std::chrono::seconds(10));
    EXPECT_THAT(server_->log(), ::testing::HasSubstr("interrupted"));
  }
}

TEST_F(ViewServer, ListeningBeyondLoopbackWarns) {
  start({"--host", "0.0.0.0"});
  EXPECT_EQ(get("/info")->status, 200);
  EXPECT_THAT(server_->log(), ::testing::HasSubstr("warning: listening on 0.0.0.0"));
}

TEST_F(ViewServer, ATakenPortIsAnError) {
  start();
  const std::string port = std::to_string(port_);
  ViewProcess second({path("scene.relume"), "--port", port}, path("second.log"));
  EXPECT_EQ(second.wait_exit(), 1);
  EXPECT_THAT(second.log(), ::testing::HasSubstr("cannot listen on 127.0.0.1 port " + port));
}

}  // namespace
}  // namespace relume
