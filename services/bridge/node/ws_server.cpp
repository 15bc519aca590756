#include "ws_server.hpp"

#include <chrono>
#include <deque>
#include <map>
#include <mutex>
#include <set>
#include <utility>  // before Asio: Boost 1.74's awaitable.hpp uses std::exchange without including it

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <spdlog/spdlog.h>

#include "twinslam/bridge/static_files.hpp"

namespace twinslam::bridge {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;

namespace {

struct Latched {
  std::uint64_t time_ns = 0;
  std::shared_ptr<const std::vector<std::uint8_t>> payload;
};

struct Shared {  // written on the I/O thread only, but clients (atomic)
  std::vector<Channel> channels;
  std::map<std::uint32_t, std::map<std::string, Latched>> latched;  // channel -> latch key -> last message
  std::string name, session_id;
  std::filesystem::path web_root;
  std::size_t max_queued = 0;
  dds::Counters* counters = nullptr;
  std::atomic<std::uint64_t> clients{0};
};

// One client. Everything runs on the server's single I/O thread (publish() posts to it), so no member needs a lock.
class Session : public std::enable_shared_from_this<Session> {
 public:
  Session(tcp::socket socket, Shared& shared)
      : ws_(std::move(socket)), shared_(shared), subs_(channel_ids(shared.channels)) {}

  void start() {
    http::async_read(ws_.next_layer(), buffer_, request_,
                     [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_request(ec); });
  }

  void publish(std::uint32_t channel, std::uint64_t time_ns, const std::vector<std::uint8_t>& payload) {
    if (!open_) return;
    for (const std::uint32_t sub : subs_.subscriptions_of(channel)) {
      queue(std::make_shared<std::vector<std::uint8_t>>(message_data(sub, time_ns, payload.data(), payload.size())));
    }
  }

  // Channels added after this client was accepted: advertised to it now (an unaccepted client gets the whole list
  // when accepted).
  void advertise(const std::vector<Channel>& added) {
    if (!open_) return;
    std::vector<std::uint32_t> ids;
    for (const Channel& c : added) ids.push_back(c.id);
    subs_.add_channels(ids);
    queue_text(advertise_json(added));
  }

  bool closed() const { return closed_; }
  void close() {
    beast::error_code ignored;
    beast::get_lowest_layer(ws_).socket().close(ignored);
  }

 private:
  struct Frame {
    std::shared_ptr<const void> keep;  // the bytes stay alive until written
    asio::const_buffer bytes;
    bool text = false;
  };

  static std::set<std::uint32_t> channel_ids(const std::vector<Channel>& channels) {
    std::set<std::uint32_t> ids;
    for (const Channel& c : channels) ids.insert(c.id);
    return ids;
  }

  void on_request(beast::error_code ec) {
    if (ec) return fail("handshake", ec);
    if (!websocket::is_upgrade(request_)) return serve_file();
    // The spec: the server must select a subprotocol the client offered; Foxglove offers foxglove.websocket.v1.
    const std::string offered(request_[http::field::sec_websocket_protocol]);
    if (offered.find(kSubprotocol) == std::string::npos) {
      spdlog::warn("bridge: a client without the {} subprotocol was refused", kSubprotocol);
      return close();
    }
    ws_.set_option(websocket::stream_base::decorator([](websocket::response_type& res) {
      res.set(http::field::sec_websocket_protocol, kSubprotocol);
    }));
    ws_.async_accept(request_, [self = shared_from_this()](beast::error_code e) { self->on_accept(e); });
  }

  // Plain HTTP on the same port: the web view's files (static_files.hpp), one request per connection.
  void serve_file() {
    StaticReply r = serve_static(shared_.web_root, std::string(request_.method_string()), std::string(request_.target()));
    auto res = std::make_shared<http::response<http::string_body>>(static_cast<http::status>(r.status),
                                                                    request_.version());
    res->set(http::field::server, "twinslam-bridge");
    res->set(http::field::content_type, r.content_type);
    res->set(http::field::cache_control, "no-cache");  // a rebuilt view must not be shadowed by a cached one
    res->keep_alive(false);
    if (request_.method() == http::verb::head) {
      res->content_length(r.body.size());
    } else {
      res->body() = std::move(r.body);
      res->prepare_payload();
    }
    http::async_write(ws_.next_layer(), *res, [self = shared_from_this(), res](beast::error_code e, std::size_t) {
      self->fail("http", e);
      self->close();
    });
  }

  void on_accept(beast::error_code ec) {
    if (ec) return fail("accept", ec);
    open_ = true;
    subs_ = ClientSubscriptions(channel_ids(shared_.channels));  // those advertised since the session began too
    ++shared_.clients;
    shared_.counters->add("clients_accepted");
    queue_text(server_info_json(shared_.name, shared_.session_id));
    queue_text(advertise_json(shared_.channels));
    read();
  }

  void read() {
    ws_.async_read(in_, [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
  }

  void on_read(beast::error_code ec) {
    if (ec) return fail("read", ec);
    if (ws_.got_text()) {
      const auto before = subs_.subscriptions();
      for (std::string& status : subs_.apply(beast::buffers_to_string(in_.data()))) queue_text(std::move(status));
      for (const auto& [sub, channel] : subs_.subscriptions()) {
        if (before.count(sub) == 0) send_latched(sub, channel);
      }
    }
    in_.consume(in_.size());
    read();
  }

  // A new subscription first gets the kept (latched) messages of its channel.
  void send_latched(std::uint32_t sub, std::uint32_t channel) {
    const auto it = shared_.latched.find(channel);
    if (it == shared_.latched.end()) return;
    for (const auto& [key, m] : it->second) {
      queue(std::make_shared<std::vector<std::uint8_t>>(
          message_data(sub, m.time_ns, m.payload->data(), m.payload->size())));
    }
  }

  void queue_text(std::string text) {
    auto keep = std::make_shared<std::string>(std::move(text));
    push({keep, asio::buffer(*keep), true});
  }
  void queue(std::shared_ptr<std::vector<std::uint8_t>> bytes) { push({bytes, asio::buffer(*bytes), false}); }

  void push(Frame f) {
    if (closed_) return;
    if (out_.size() >= shared_.max_queued && out_.size() > 1) {
      out_.erase(out_.begin() + 1);  // the oldest not being written
      shared_.counters->add("frames_dropped");
    }
    out_.push_back(std::move(f));
    if (out_.size() == 1) write();
  }

  void write() {
    ws_.text(out_.front().text);
    ws_.async_write(out_.front().bytes, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) return self->fail("write", ec);
      if (!self->out_.front().text) self->shared_.counters->add("frames_sent");
      self->out_.pop_front();
      if (!self->out_.empty()) self->write();
    });
  }

  // The queue is left as it is: a write may still be in flight on its front frame.
  void fail(const char* what, beast::error_code ec) {
    if (closed_) return;
    if (open_) --shared_.clients;
    if (ec && ec != websocket::error::closed && ec != asio::error::eof && ec != asio::error::operation_aborted) {
      spdlog::info("bridge: client left ({}: {})", what, ec.message());
    }
    closed_ = true;
    open_ = false;
  }

  websocket::stream<beast::tcp_stream> ws_;
  Shared& shared_;
  ClientSubscriptions subs_;
  beast::flat_buffer buffer_, in_;
  http::request<http::string_body> request_;
  std::deque<Frame> out_;
  bool open_ = false, closed_ = false;
};

}  // namespace

struct WsServer::Impl {
  asio::io_context io{1};
  tcp::acceptor acceptor{io};
  Shared shared;
  std::vector<std::weak_ptr<Session>> sessions;  // I/O thread only
  std::thread thread;

  void accept() {
    acceptor.async_accept([this](beast::error_code ec, tcp::socket socket) {
      if (ec) return;  // the acceptor was closed: the server is stopping
      auto s = std::make_shared<Session>(std::move(socket), shared);
      std::erase_if(sessions, [](const std::weak_ptr<Session>& w) { return w.expired() || w.lock()->closed(); });
      sessions.push_back(s);
      s->start();
      accept();
    });
  }
};

WsServer::WsServer(const std::string& address, unsigned short port, std::vector<Channel> channels, std::string name,
                   std::size_t max_queued, dds::Counters& counters, std::filesystem::path web_root)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.shared.channels = std::move(channels);
  m.shared.name = std::move(name);
  m.shared.web_root = std::move(web_root);
  m.shared.session_id = std::to_string(std::chrono::system_clock::now().time_since_epoch().count());
  m.shared.max_queued = max_queued;
  m.shared.counters = &counters;
  try {
    const tcp::endpoint at(asio::ip::make_address(address), port);
    m.acceptor.open(at.protocol());
    m.acceptor.set_option(asio::socket_base::reuse_address(true));
    m.acceptor.bind(at);
    m.acceptor.listen();
  } catch (const std::exception& e) {
    throw std::runtime_error("bridge: cannot listen on " + address + ":" + std::to_string(port) + ": " + e.what());
  }
  m.accept();
  m.thread = std::thread([&m] { m.io.run(); });
}

WsServer::~WsServer() {
  // On the I/O thread: close everything, then stop; handlers still pending are destroyed with the io_context.
  asio::post(impl_->io, [m = impl_.get()] {
    beast::error_code ignored;
    m->acceptor.close(ignored);
    for (auto& w : m->sessions) {
      if (auto s = w.lock()) s->close();
    }
    m->io.stop();
  });
  if (impl_->thread.joinable()) impl_->thread.join();
}

unsigned short WsServer::port() const { return impl_->acceptor.local_endpoint().port(); }

void WsServer::publish(std::uint32_t channel_id, std::uint64_t receive_time_ns,
                       std::shared_ptr<const std::vector<std::uint8_t>> payload,
                       const std::optional<std::string>& latch_key) {
  if (!latch_key && impl_->shared.clients.load() == 0) return;  // nobody listens: not even a post
  asio::post(impl_->io, [m = impl_.get(), channel_id, receive_time_ns, payload = std::move(payload), latch_key] {
    if (latch_key) m->shared.latched[channel_id][*latch_key] = {receive_time_ns, payload};
    for (auto& w : m->sessions) {
      if (auto s = w.lock()) s->publish(channel_id, receive_time_ns, *payload);
    }
  });
}

void WsServer::advertise(std::vector<Channel> channels) {
  asio::post(impl_->io, [m = impl_.get(), channels = std::move(channels)] {
    m->shared.channels.insert(m->shared.channels.end(), channels.begin(), channels.end());
    for (auto& w : m->sessions) {
      if (auto s = w.lock()) s->advertise(channels);
    }
  });
}

std::uint64_t WsServer::clients() const { return impl_->shared.clients.load(); }

}  // namespace twinslam::bridge
