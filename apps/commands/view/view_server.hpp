// The HTTP server of `relume view` (cpp-httplib): the page and its script and style at `/`,
// `/viewer.js`, `/viewer.css`, the field's description at `GET /info` and frames at `GET /frame`
// (docs/viewer.md). A bad request gets 400 with a message naming the parameter, an unknown path
// 404, too many requests 429 (request_rate_limit.hpp), a failed render 500; none of them stops the
// server. It serves until an interruption is requested (SIGINT or SIGTERM through
// core/signals.hpp), then stops listening, lets the requests in progress finish and returns.
#pragma once

#include <string>

#include "commands/view/viewer.hpp"

namespace relume {

struct ServerSettings {
  std::string host = "127.0.0.1";
  int port = 8080;  // 0: any free port
  double requests_per_second = 120;
};

// Binds the address, prints it on stdout ("relume view: http://HOST:PORT/"), warns on stderr
// when the host is not a loopback address, and serves `viewer` until interrupted. Throws Error
// when the address cannot be bound.
void serve_viewer(Viewer& viewer, const ServerSettings& settings);

// True for addresses only this machine reaches: localhost, 127.x.x.x, ::1.
bool is_loopback_host(const std::string& host);

}  // namespace relume
