// `twinslam view [--host H] [--port P] [--no-open]`: opens the built-in web view of a running bridge
// (`twinslam run ... --bridge P`, or twinslam-bridge in a launch file), served on the bridge's WebSocket port. It
// first asks the bridge for the page, so a missing bridge or an unbuilt view is one clear line, not a blank tab.
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange without including it

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

#include "commands.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/core/main_guard.hpp"

namespace twinslam::cli {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;

struct ViewOptions {
  std::string host = "127.0.0.1";
  int port = 8765;
  bool open = true;
};

// GET / from the bridge: its status and body; UsageError when nothing answers there.
std::pair<unsigned, std::string> fetch_page(const ViewOptions& o) {
  try {
    asio::io_context io;
    asio::ip::tcp::resolver resolver(io);
    beast::tcp_stream stream(io);
    stream.expires_after(std::chrono::seconds(5));
    stream.connect(resolver.resolve(o.host, std::to_string(o.port)));
    http::request<http::empty_body> req{http::verb::get, "/", 11};
    req.set(http::field::host, o.host);
    http::write(stream, req);
    beast::flat_buffer buffer;
    http::response<http::string_body> res;
    http::read(stream, buffer, res);
    return {res.result_int(), res.body()};
  } catch (const std::exception& e) {
    throw UsageError("no bridge answers at " + o.host + ":" + std::to_string(o.port) + " (" + e.what() +
                     "): start one with `twinslam run ... --bridge " + std::to_string(o.port) + "` or twinslam-bridge");
  }
}

// Only host names and addresses reach the shell (the URL is passed to xdg-open).
bool plain_host(const std::string& host) {
  if (host.empty()) return false;
  for (char c : host) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != ':') return false;
  }
  return true;
}

int run_view(const ViewOptions& o) {
  if (!plain_host(o.host)) throw UsageError("--host '" + o.host + "': expected a host name or an IP address");
  const auto [status, body] = fetch_page(o);
  if (status != 200) {  // e.g. 404 "web view not built: ..."
    std::fprintf(stderr, "twinslam view: the bridge at %s:%d answered %u: %s", o.host.c_str(), o.port, status,
                 body.c_str());
    return kExitBadInput;
  }
  const std::string url = "http://" + (o.host.find(':') != std::string::npos ? "[" + o.host + "]" : o.host) + ":" +
                          std::to_string(o.port) + "/";
  std::printf("web view: %s\n", url.c_str());
  const bool display = std::getenv("DISPLAY") != nullptr || std::getenv("WAYLAND_DISPLAY") != nullptr;
  if (!o.open) return kExitOk;
  if (!display) {
    std::printf("no display here: open %s in a browser (for a remote bridge, forward the port: ssh -L)\n", url.c_str());
    return kExitOk;
  }
  if (std::system(("xdg-open '" + url + "' >/dev/null 2>&1 &").c_str()) != 0) {
    std::printf("could not start a browser (xdg-open): open %s yourself\n", url.c_str());
  }
  return kExitOk;
}

}  // namespace

void add_view_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("view", "Open the web view of a running bridge (twinslam run --bridge PORT)");
  auto o = std::make_shared<ViewOptions>();
  cmd->add_option("--host", o->host, "Host of the bridge")->capture_default_str();
  cmd->add_option("--port", o->port, "The bridge's port (twinslam run --bridge PORT)")
      ->check(CLI::Range(1, 65535))
      ->capture_default_str();
  cmd->add_flag("!--no-open", o->open, "Only check the view and print its URL");
  cmd->callback([o, &exit_code] { exit_code = run_view(*o); });
}

}  // namespace twinslam::cli
