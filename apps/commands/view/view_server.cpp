// Implementation of the viewer's HTTP server (view_server.hpp).
#include "commands/view/view_server.hpp"

// After Eigen (included by view_server.hpp): httplib.h brings in <resolv.h>, whose _res macro
// breaks Eigen's headers.
#include <httplib.h>
#include <sys/socket.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <thread>

#include "core/console.hpp"
#include "core/interruption.hpp"
#include "commands/view/request_rate_limit.hpp"
#include "commands/view/viewer_page.hpp"

namespace relume {
namespace {

constexpr const char* text_type = "text/plain; charset=utf-8";

// `handle` with every exception turned into an answer: BadRequest 400, anything else 500 (and a
// line on stderr, since it is the server's fault).
httplib::Server::Handler answered(
    std::function<void(const httplib::Request&, httplib::Response&)> handle) {
  return [handle](const httplib::Request& request, httplib::Response& response) {
    try {
      handle(request, response);
    } catch (const BadRequest& e) {
      response.status = 400;
      response.set_content(std::string(e.what()) + "\n", text_type);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "relume view: error: %s %s: %s\n", request.method.c_str(),
                   request.target.c_str(), e.what());
      response.status = 500;
      response.set_content(std::string("error: ") + e.what() + "\n", text_type);
    }
  };
}

httplib::Server::Handler page_file(const std::string& text, const char* type) {
  return [&text, type](const httplib::Request&, httplib::Response& response) {
    response.set_content(text, type);
  };
}

void add_routes(httplib::Server& server, Viewer& viewer, const ServerSettings& settings) {
  server.Get("/", page_file(viewer_page_html(), "text/html; charset=utf-8"));
  server.Get("/viewer.js", page_file(viewer_page_script(), "text/javascript; charset=utf-8"));
  server.Get("/viewer.css", page_file(viewer_page_style(), "text/css; charset=utf-8"));
  const double requests_per_second = settings.requests_per_second;
  server.Get("/info", answered([&viewer, requests_per_second](const httplib::Request&,
                                                              httplib::Response& response) {
               nlohmann::ordered_json info = viewer.info();
               info["requests_per_second"] = requests_per_second;
               response.set_content(info.dump(), "application/json");
             }));
  server.Get("/frame",
             answered([&viewer](const httplib::Request& request, httplib::Response& response) {
               EncodedFrame frame = viewer.frame(request.params);
               for (const auto& [name, value] : frame.headers) response.set_header(name, value);
               response.set_header("Cache-Control", "no-store");
               response.set_content(std::move(frame.bytes), frame.content_type);
             }));
  server.Get(".*", [](const httplib::Request& request, httplib::Response& response) {
    response.status = 404;
    response.set_content(
        "no such page: " + request.path + " (relume view serves /, /info and /frame)\n", text_type);
  });
}

// "http://HOST:PORT/", with an IPv6 host in brackets.
std::string address(const std::string& host, int port) {
  const bool ipv6 = host.find(':') != std::string::npos;
  return "http://" + (ipv6 ? "[" + host + "]" : host) + ":" + std::to_string(port) + "/";
}

void wait_for(const std::function<bool()>& done) {
  while (!done()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
}

}  // namespace

bool is_loopback_host(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

void serve_viewer(Viewer& viewer, const ServerSettings& settings) {
  // A client that goes away mid-answer must not end the server with SIGPIPE.
  std::signal(SIGPIPE, SIG_IGN);
  httplib::Server server;
  RequestRateLimit rate_limit(settings.requests_per_second);
  // SO_REUSEADDR only: httplib's default SO_REUSEPORT would let a second server (anyone's) bind
  // the same port and take a share of the connections.
  server.set_socket_options([](int socket) {
    const int yes = 1;
    setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  server.set_tcp_nodelay(true);  // frames go out at once, not after a delayed ACK
  server.set_keep_alive_max_count(1000);
  server.set_payload_max_length(64 * 1024);  // only GETs: no request has a body worth keeping
  server.set_pre_routing_handler(
      [&rate_limit](const httplib::Request&, httplib::Response& response) {
        if (rate_limit.admit()) return httplib::Server::HandlerResponse::Unhandled;
        response.status = 429;
        response.set_header("Retry-After", "1");
        response.set_content("too many requests: relume view answers at most " +
                                 std::to_string(int(rate_limit.per_second())) + " a second\n",
                             text_type);
        return httplib::Server::HandlerResponse::Handled;
      });
  server.set_logger([](const httplib::Request& request, const httplib::Response& response) {
    detail("relume view: %s %s %d", request.method.c_str(), request.target.c_str(),
           response.status);
  });
  add_routes(server, viewer, settings);

  const int port = settings.port == 0 ? server.bind_to_any_port(settings.host)
                   : server.bind_to_port(settings.host, settings.port) ? settings.port
                                                                       : -1;
  if (port <= 0)
    throw Error("cannot listen on " + settings.host + " port " + std::to_string(settings.port) +
                " (the port is in use, or the host is not an address of this machine)");
  if (!is_loopback_host(settings.host))
    std::fprintf(stderr,
                 "relume view: warning: listening on %s, which other machines may reach: anyone "
                 "who can connect sees the field and can keep the renderer busy\n",
                 settings.host.c_str());
  std::printf("relume view: %s\n", address(settings.host, port).c_str());
  std::fflush(stdout);
  note("relume view: serving %s; Ctrl-C stops", address(settings.host, port).c_str());

  std::atomic<bool> listener_returned{false};
  std::thread listener([&] {
    server.listen_after_bind();
    listener_returned = true;
  });
  // stop() only acts on a running server: wait until it runs, then for the interruption.
  wait_for([&] { return server.is_running() || listener_returned; });
  wait_for([&] { return interruption_requested() || listener_returned; });
  server.stop();
  listener.join();
  if (!interruption_requested())
    throw Error("the server on " + address(settings.host, port) + " stopped unexpectedly");
}

}  // namespace relume
