// The bridge's WebSocket server over a real socket, with a Beast client speaking the Foxglove protocol: what a viewer
// that connects late must still get (latched twin tiles, first, on subscribing) and channels that appear while it
// is connected (advertised to it at once, then subscribable). The full pipeline is test_bridge_run's.
#include <chrono>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange without including it

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ws_server.hpp"

namespace twinslam::bridge {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
using tcp = asio::ip::tcp;
using nlohmann::json;

std::shared_ptr<const std::vector<std::uint8_t>> bytes(const std::string& text) {
  return std::make_shared<const std::vector<std::uint8_t>>(text.begin(), text.end());
}

class Client {
 public:
  explicit Client(unsigned short port) : ws_(io_) {
    tcp::resolver resolver(io_);
    asio::connect(ws_.next_layer(), resolver.resolve("127.0.0.1", std::to_string(port)));
    ws_.set_option(beast::websocket::stream_base::decorator([](beast::websocket::request_type& req) {
      req.set(beast::http::field::sec_websocket_protocol, kSubprotocol);
    }));
    ws_.handshake("127.0.0.1", "/");
  }
  // The next frame: text as it is, binary Message Data as "sub=<id> payload=<text>".
  std::string next() {
    // A frame that never comes fails the test instead of hanging it.
    beast::flat_buffer b;
    bool done = false;
    beast::error_code error;
    ws_.async_read(b, [&](beast::error_code ec, std::size_t) { done = true; error = ec; });
    io_.restart();
    io_.run_for(std::chrono::seconds(10));
    if (!done) throw std::runtime_error("no frame within 10 s");
    if (error) throw beast::system_error(error);
    const std::string data = beast::buffers_to_string(b.data());
    if (ws_.got_text()) return data;
    std::uint32_t sub = 0;
    std::memcpy(&sub, data.data() + 1, 4);
    return "sub=" + std::to_string(sub) + " payload=" + data.substr(13);
  }
  void send(const json& j) {
    ws_.text(true);
    ws_.write(asio::buffer(j.dump()));
  }

 private:
  asio::io_context io_;
  beast::websocket::stream<tcp::socket> ws_;
};

json subscribe(std::uint32_t id, std::uint32_t channel) {
  return {{"op", "subscribe"}, {"subscriptions", {{{"id", id}, {"channelId", channel}}}}};
}

TEST(BridgeWsServer, ALateViewerGetsEveryLatchedTileAndChannelsAdvertisedWhileItWatches) {
  dds::Counters counters;
  WsServer server("127.0.0.1", 0, {{1, "tiles", "json", "foxglove.SceneUpdate", "jsonschema", "{}"}}, "test", 100,
                  counters);
  // Before anyone connects: two tiles, one of them replaced; a message on no latch is not kept.
  server.publish(1, 10, bytes("tile A v1"), "A");
  server.publish(1, 11, bytes("tile B"), "B");
  server.publish(1, 12, bytes("tile A v2"), "A");
  server.publish(1, 13, bytes("not kept"));

  Client client(server.port());
  EXPECT_EQ(json::parse(client.next())["op"], "serverInfo");
  const json advertised = json::parse(client.next());
  ASSERT_EQ(advertised["channels"].size(), 1u);
  client.send(subscribe(7, 1));
  // The latched tiles, newest of each key, in key order.
  EXPECT_EQ(client.next(), "sub=7 payload=tile A v2");
  EXPECT_EQ(client.next(), "sub=7 payload=tile B");

  // A channel that appears now is advertised to the connected client and can be subscribed.
  server.advertise({{2, "/uav3/estimate/pose", "json", "foxglove.PoseInFrame", "jsonschema", "{}"}});
  const json later = json::parse(client.next());
  EXPECT_EQ(later["op"], "advertise");
  ASSERT_EQ(later["channels"].size(), 1u);
  EXPECT_EQ(later["channels"][0]["topic"], "/uav3/estimate/pose");
  client.send(subscribe(8, 2));
  // The server applies a client's messages in order: once this one is answered, the subscription is in place.
  client.send({{"op", "no such op"}});
  EXPECT_EQ(json::parse(client.next())["op"], "status");
  server.publish(2, 20, bytes("pose"));
  EXPECT_EQ(client.next(), "sub=8 payload=pose");
  EXPECT_EQ(counters.get("clients_accepted"), 1u);
}

// A plain HTTP GET on the bridge's port; the status and body of the answer.
std::pair<unsigned, std::string> http_get(unsigned short port, const std::string& target) {
  asio::io_context io;
  beast::tcp_stream stream(io);
  tcp::resolver resolver(io);
  stream.expires_after(std::chrono::seconds(10));
  stream.connect(resolver.resolve("127.0.0.1", std::to_string(port)));
  beast::http::request<beast::http::empty_body> req{beast::http::verb::get, target, 11};
  req.set(beast::http::field::host, "127.0.0.1");
  beast::http::write(stream, req);
  beast::flat_buffer buffer;
  beast::http::response<beast::http::string_body> res;
  beast::http::read(stream, buffer, res);
  return {res.result_int(), res.body()};
}

TEST(BridgeWsServer, TheWebViewIsServedOnTheSamePortAsTheProtocol) {
  const auto root = std::filesystem::temp_directory_path() / ("twinslam_ws_web_" + std::to_string(::getpid()));
  std::filesystem::create_directories(root);
  std::ofstream(root / "index.html") << "<title>twinslam</title>";
  std::ofstream(root / "app.js") << "let x = 1;";
  dds::Counters counters;
  WsServer server("127.0.0.1", 0, {}, "test", 100, counters, root);
  EXPECT_EQ(http_get(server.port(), "/"), std::make_pair(200u, std::string("<title>twinslam</title>")));
  EXPECT_EQ(http_get(server.port(), "/app.js").second, "let x = 1;");
  EXPECT_EQ(http_get(server.port(), "/../etc/passwd").first, 400u);
  Client client(server.port());  // and a Foxglove client on the same port, after the page
  EXPECT_EQ(json::parse(client.next())["op"], "serverInfo");
  std::filesystem::remove_all(root);
}

}  // namespace
}  // namespace twinslam::bridge
