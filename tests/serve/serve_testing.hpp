#pragma once
// Test helpers for legwork serve: a server on a free loopback port in this
// process, and a small Boost.Beast WebSocket client whose every read has a
// deadline (a broken server fails the test instead of hanging it).
#include <legwork/serve/protocol.hpp>
#include <legwork/serve/server.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <utility>  // before Asio (Boost 1.74 awaitable.hpp needs std::exchange)

#include <boost/asio.hpp>
#include <boost/beast.hpp>

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <thread>

namespace legwork::serve::testing {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using json = nlohmann::json;

inline std::string source_dir() { return LEGWORK_SOURCE_DIR; }

// Options for a test server: ik on the CMU 07_01 skeleton, port 0, no rate limit
// unless a test asks for one (lock-step clients run far above 120 Hz).
inline ServeOptions test_options() {
  ServeOptions o;
  o.port = 0;
  o.skeleton_path = source_dir() + "/data/cmu/bvh/walking/07_01.bvh";
  o.trials_dir = source_dir() + "/data/cmu/bvh";
  o.max_rate_hz = 1e6;
  return o;
}

// A Server running on its own thread; stopped and joined on destruction.
class RunningServer {
 public:
  explicit RunningServer(ServeOptions o = test_options()) : server_(std::move(o)) {
    thread_ = std::thread([this] { server_.run(); });
  }
  ~RunningServer() { stop(); }
  void stop() {
    if (!thread_.joinable()) return;
    server_.stop();
    thread_.join();
  }
  unsigned short port() const { return server_.port(); }
  Server& server() { return server_; }

 private:
  Server server_;
  std::thread thread_;
};

class Client {
 public:
  struct Message {
    bool binary = false;
    std::string data;
    json j() const { return json::parse(data); }
  };

  explicit Client(unsigned short port, const std::string& target = "/ws") : ws_(ioc_) {
    tcp::resolver r(ioc_);
    net::connect(beast::get_lowest_layer(ws_).socket(), r.resolve("127.0.0.1", std::to_string(port)));
    beast::get_lowest_layer(ws_).socket().set_option(tcp::no_delay(true));
    ws_.handshake("127.0.0.1:" + std::to_string(port), target);
    ws_.read_message_max(8u << 20);
  }

  void send_text(const std::string& s) {
    ws_.text(true);
    ws_.write(net::buffer(s));
  }
  void send_binary(const std::string& s) {
    ws_.binary(true);
    ws_.write(net::buffer(s));
  }
  // The next message, or nullopt after `timeout` or when the connection ended
  // (then closed() / close_code() tell why).
  std::optional<Message> read(std::chrono::milliseconds timeout = std::chrono::milliseconds(5000)) {
    beast::flat_buffer buf;
    std::optional<beast::error_code> result;
    ws_.async_read(buf, [&](beast::error_code ec, std::size_t) { result = ec; });
    ioc_.restart();
    ioc_.run_for(timeout);
    if (!result) {
      beast::get_lowest_layer(ws_).cancel();
      ioc_.restart();
      ioc_.run_for(timeout);  // bounded: an operation suspended inside Beast is not cancelled
      return std::nullopt;
    }
    if (*result) {
      error_ = *result;
      return std::nullopt;
    }
    return Message{!ws_.got_text(), beast::buffers_to_string(buf.data())};
  }
  // Reads until a message of `type` (JSON) arrives; fails the test otherwise.
  json expect(const std::string& type, std::chrono::milliseconds timeout = std::chrono::milliseconds(5000)) {
    for (;;) {
      auto m = read(timeout);
      if (!m) {
        ADD_FAILURE() << "no '" << type << "' message (connection: " << error_.message() << ")";
        return json::object();
      }
      if (m->binary) continue;
      json j = m->j();
      if (j.value("type", "") == type) return j;
    }
  }
  json hello(const json& extra = json::object()) {
    json h = {{"type", "hello"}, {"version", 1}, {"method", "ik"}};
    h.update(extra);
    send_text(h.dump());
    return expect("welcome");
  }
  const beast::error_code& error() const { return error_; }
  int close_code() const { return ws_.reason().code; }
  void close() { ws_.close(websocket::close_code::normal); }
  // Drops the TCP connection without a WebSocket close (a client vanishing).
  void vanish() {
    beast::error_code ec;
    beast::get_lowest_layer(ws_).socket().close(ec);
  }

 private:
  net::io_context ioc_;
  websocket::stream<beast::tcp_stream> ws_;
  beast::error_code error_;
};

}  // namespace legwork::serve::testing
